// caustica denoise IN -o OUT — denoise a rendered image into a new file (the input is kept).
#include <tbb/global_control.h>

#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "caustica/render/denoise_file.h"

namespace caustica::cli {

std::function<int()> addDenoiseCommand(CLI::App& app) {
    struct Options {
        std::string input, output, method = "nlm", albedo, normal, depth, variance, oidnLibrary;
        bool ignoreLayers = false, quiet = false;
        int threads = 0;
        NlmParams nlm;
    };
    auto opt = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("denoise", "Denoise a rendered image into a new file (the input is kept)");
    cmd->add_option("image", opt->input,
                    "Noisy image (.exr, .pfm); an EXR's AOV layers are used as guides; a multi-view (stereo) "
                    "EXR is denoised view by view into a multi-view EXR")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", opt->output, "Denoised image (.exr, .pfm, .png); never the input")->required();
    cmd->add_option("--method", opt->method, "Denoiser: nlm (feature-guided NL-means, built in) or oidn (Intel "
                                             "Open Image Denoise, loaded at run time)");
    cmd->add_option("--albedo", opt->albedo, "Albedo image (overrides the input's albedo layer)");
    cmd->add_option("--normal", opt->normal, "Shading-normal image (overrides the input's normal layer)");
    cmd->add_option("--depth", opt->depth, "Depth image, first channel (overrides the input's depth layer)");
    cmd->add_option("--variance", opt->variance, "Per-pixel variance of the mean (nlm; else estimated)");
    cmd->add_flag("--ignore-layers", opt->ignoreLayers, "Do not use the input EXR's AOV layers");
    cmd->add_option("--oidn-library", opt->oidnLibrary, "Path of libOpenImageDenoise (else CAUSTICA_OIDN_LIBRARY, "
                                                        "a pyoidn install, the system's library path)");
    cmd->add_option("--threads", opt->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
    cmd->add_option("--radius", opt->nlm.radius, "nlm: search window radius in pixels")->check(CLI::Range(0, 64));
    cmd->add_option("--patch-radius", opt->nlm.patchRadius, "nlm: patch radius in pixels")->check(CLI::Range(0, 8));
    cmd->add_option("--k-color", opt->nlm.kColor, "nlm: colour sensitivity k_c (smaller keeps more detail)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--k-feature", opt->nlm.kFeature, "nlm: feature sensitivity k_f")->check(CLI::PositiveNumber);
    cmd->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
    return [opt] {
        DenoiseSettings settings;
        settings.method = parseDenoiseMethod(opt->method);
        settings.nlm = opt->nlm;
        settings.oidn.library = opt->oidnLibrary;
        settings.oidn.threads = opt->threads;
        std::unique_ptr<tbb::global_control> threads;
        if (opt->threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            size_t(opt->threads));
        const DenoiseFileResult r = denoiseFile(
            DenoiseFileRequest{opt->input, opt->output, opt->albedo, opt->normal, opt->depth, opt->variance,
                               opt->ignoreLayers},
            settings);
        if (!opt->quiet)
            std::printf("denoised %s (%d x %d%s, %s; guides:%s%s%s%s%s) -> %s\n", opt->input.c_str(), r.width,
                        r.height, r.views == 2 ? ", views left and right" : "", denoiseMethodName(settings.method),
                        r.albedo ? " albedo" : "", r.normal ? " normal" : "", r.depth ? " depth" : "",
                        r.variance ? " variance" : "", r.albedo || r.normal || r.depth || r.variance ? "" : " none",
                        opt->output.c_str());
        return 0;
    };
}

}  // namespace caustica::cli
