// caustica denoise IN -o OUT — denoise a rendered image into a new file (the input is kept).
#include <tbb/global_control.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.h"
#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/image_io.h"
#include "caustica/render/denoise.h"
#include "caustica/render/render_outputs.h"
#include "caustica/util/error.h"

namespace caustica::cli {

namespace {

bool isExr(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".exr";
}

/// Refuses an output that is the input itself (the noisy image is always kept).
void checkNotInput(const std::string& input, const std::string& output) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const bool same = fs::exists(output, ec) ? fs::equivalent(input, output, ec)
                                             : fs::weakly_canonical(input, ec) == fs::weakly_canonical(output, ec);
    if (same) throw Error(output, 0, "the output would overwrite the noisy input: give another -o path");
}

}  // namespace

std::function<int()> addDenoiseCommand(CLI::App& app) {
    struct Options {
        std::string input, output, method = "nlm", albedo, normal, depth, variance, oidnLibrary;
        bool ignoreLayers = false, quiet = false;
        int threads = 0;
        NlmParams nlm;
    };
    auto opt = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("denoise", "Denoise a rendered image into a new file (the input is kept)");
    cmd->add_option("image", opt->input, "Noisy image (.exr, .pfm); an EXR's AOV layers are used as guides")
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
        checkNotInput(opt->input, opt->output);
        checkImageOutputPath(opt->output);

        std::unique_ptr<tbb::global_control> threads;
        if (opt->threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            size_t(opt->threads));
        const Image color = readImage(opt->input);
        DenoiseFeatures features;
        if (!opt->ignoreLayers && isExr(opt->input)) features = readFeatureLayers(opt->input);
        if (!opt->albedo.empty()) features.albedo = readImage(opt->albedo);
        if (!opt->normal.empty()) features.normal = readImage(opt->normal, ImageReadOptions{.raw = true});
        if (!opt->depth.empty()) features.depth = readImage(opt->depth);
        if (!opt->variance.empty()) features.variance = readImage(opt->variance);

        const Image result = denoise(color, features, settings);
        ImageMetadata metadata = readImageMetadata(opt->input);
        metadata.entries.erase(kAovsAttribute);  // the output holds the colour only
        metadata.entries["caustica.denoiser"] = denoiseMethodName(settings.method);
        metadata.entries["caustica.denoised_from"] = opt->input;
        writeImage(opt->output, result, metadata);
        if (!opt->quiet)
            std::printf("denoised %s (%d x %d, %s; guides:%s%s%s%s%s) -> %s\n", opt->input.c_str(), color.width,
                        color.height, denoiseMethodName(settings.method), features.albedo ? " albedo" : "",
                        features.normal ? " normal" : "", features.depth ? " depth" : "",
                        features.variance ? " variance" : "",
                        features.albedo || features.normal || features.depth || features.variance ? "" : " none",
                        opt->output.c_str());
        return 0;
    };
}

}  // namespace caustica::cli
