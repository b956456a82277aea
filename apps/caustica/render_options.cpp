#include "render_options.h"

#include <cmath>
#include <cstdio>

#include "commands.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/util/error.h"

namespace caustica::cli {

CLI::Validator finiteRange(double lo, double hi, const std::string& bounds) {
    return CLI::Validator(
        [lo, hi, bounds](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0') return "'" + text + "' is not a number";
            if (!std::isfinite(v) || v < lo || v > hi) return "'" + text + "' is not a finite number in " + bounds;
            return {};
        },
        bounds);
}

void addRenderOptions(CLI::App& cmd, RenderOptions& o) {
    RenderRequest& r = o.request;
    RunControl& c = o.control;
    cmd.add_option("scene", o.scene, "Scene file (Mitsuba 3 XML)")->required()->check(CLI::ExistingFile);
    cmd.add_option("-o,--output", c.outputs, "Output image(s): .exr (float RGB + metadata), .pfm, .png (sRGB); "
                   "repeatable. Default: SCENE_NAME.exr in the current directory");
    cmd.add_option("--spp", r.samplesPerPixel, "Samples per pixel of the whole render, resumes included (default: "
                   "the scene's sample_count; with --time alone: unlimited)")->check(CLI::Range(1, 1 << 24));
    cmd.add_option("--time", r.timeLimit, "Time budget in seconds of the whole render, resumes included; stops "
                   "after the step that reaches it")->check(finiteRange(1e-3, 1e7, "[0.001, 10000000] seconds"));
    cmd.add_option("--threads", o.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
    cmd.add_option("--seed", o.seed, "Seed of the random streams (default: the scene sampler's seed)");
    cmd.add_option("--res", o.res, "Override the film resolution, WIDTHxHEIGHT");
    cmd.add_option("-D,--define", o.defines, "Set a scene <default> parameter: -D name=value (repeatable)");
    cmd.add_option("--accel", o.accel, "Ray-tracing backend on the CPU (a GPU traces the own BVH)")
        ->check(CLI::IsMember({"embree", "bvh"}));
    cmd.add_option("--embree-isa", o.embreeIsa, "Instruction set of Embree's kernels: auto (default: the widest on "
                   "CPUs with AVX-512 whose clock it does not lower and on AMD Zen 3, else sse4.2), "
                   "widest or sse4.2")
        ->check(CLI::IsMember({"auto", "widest", "sse4.2"}));
    std::vector<std::string> names;
    for (const IntegratorEntry& e : integratorRegistry()) names.push_back(e.name);
    cmd.add_option("--integrator", r.integrator, "Integrator (overrides the scene's): " + integratorNames())
        ->check(CLI::IsMember(names));
    cmd.add_option("--path-mode", r.pathMode, "Path tracer execution on the CPU: wavefront (default) or megakernel (same image)")
        ->check(CLI::IsMember({"megakernel", "wavefront"}));
    cmd.add_option("--device", r.device, "Where to render: cpu, cuda, or auto (the GPU when this binary has the "
                   "CUDA backend and a GPU is present, else the CPU)")->check(CLI::IsMember({"cpu", "cuda", "auto"}));
    cmd.add_option("--gpu", r.gpu, "The GPU to render on with --device cuda (default: under mpirun/srun the rank's "
                   "local rank modulo the host's GPUs, one GPU per rank; else GPU 0)")->check(CLI::Range(0, 1023));
    cmd.add_option("--gpu-mode", r.gpuMode, "Path tracer execution on the GPU: wavefront (default) or megakernel (same image)")
        ->check(CLI::IsMember({"megakernel", "wavefront"}));
    cmd.add_option("--aov", r.aovs, "AOVs written as layers of the .exr output, Mitsuba's aovs list NAME:TYPE,... "
                   "(types: depth, position, uv, geo_normal, sh_normal, albedo, prim_index, shape_index, "
                   "variance; replaces the scene's aov integrator's list; docs/AOV.md)");
    cmd.add_option("--denoise", o.denoise, "Also write the final image denoised, NAME.denoised.EXT beside every "
                   "output: nlm (caustica's filter) or oidn (Intel Open Image Denoise); adds the guide AOVs "
                   "(docs/DENOISING.md)")->check(CLI::IsMember({"nlm", "oidn"}));
    cmd.add_option("--oidn-library", o.oidnLibrary, "--denoise oidn: the OpenImageDenoise library to load");
    cmd.add_flag("--kernel-stats", o.kernelStats, "Time every named kernel launch and print the table at the end");
    cmd.add_option("--stats-json", c.statsJson, "Write the final statistics as JSON to this file");
    cmd.add_option("--spp-per-pass", r.samplesPerPass, "Samples per pixel in one pass (progress and checkpoint "
                   "granularity; default: about 256k samples a pass)")->check(CLI::Range(1, 4096));
    cmd.add_option("--checkpoint-every", c.checkpointEvery, "Seconds between checkpoints (images + OUTPUT.ckpt); "
                   "0 disables")->check(finiteRange(0, 1e7, "[0, 10000000] seconds"));
    cmd.add_flag("--resume", c.resume, "Continue the render saved in OUTPUT.ckpt (same scene and settings)");
    cmd.add_flag("--overwrite", c.overwrite, "Start over although OUTPUT.ckpt of an unfinished render exists");
    cmd.add_flag("-q,--quiet", c.quiet, "No progress bar");
    cmd.add_option("--stereo", o.stereo, "Render a stereo pair (both eyes in one render; docs/STEREO.md): "
                   "off-axis, parallel or toe-in")->check(CLI::IsMember({"off-axis", "parallel", "toe-in"}));
    cmd.add_option("--interocular", o.interocular, "Stereo: distance between the eyes in scene units (default 0.065)");
    cmd.add_option("--convergence", o.convergence, "Stereo: distance of zero parallax (off-axis) or of the toe-in "
                   "point, scene units (default 1.95)");
    cmd.add_option("--stereo-output", o.stereoOutput, "Stereo .exr outputs: multiview (one file, views left and "
                   "right) or separate (NAME.left.exr, NAME.right.exr)")->check(CLI::IsMember({"multiview", "separate"}));
    cmd.add_option("--anaglyph", c.stereo.anaglyph, "Stereo: also write a red-cyan anaglyph PNG (red: left eye; "
                   "green, blue: right eye)");
    // Each integrator's own options set its parameters; checked where the scene's are.
    for (const IntegratorEntry& e : integratorRegistry())
        for (const IntegratorOption& option : e.options) {
            if (o.integratorOptions.count(option.flag)) continue;  // shared by several (sppm, ppm)
            auto& [param, value] = o.integratorOptions[option.flag];
            param = option.param;
            cmd.add_option(option.flag, value, option.help);
        }
}

void resolveRenderOptions(RenderOptions& o, const CLI::App& cmd) {
    if (cmd.get_option("--seed")->count() > 0) o.request.seed = o.seed;
    for (const auto& [flag, option] : o.integratorOptions)
        if (cmd.get_option(flag)->count() > 0)
            o.request.integratorParams.push_back({option.first, IntegratorParam::Kind::Text, option.second, flag});
    if (!o.stereo.empty()) {
        StereoSettings& s = o.request.stereo;
        s.mode = parseStereoMode(o.stereo);
        s.interocular = Float(o.interocular);
        s.convergence = Float(o.convergence);
        checkStereoSettings(s);
        o.control.stereo.enabled = true;
        o.control.stereo.separate = o.stereoOutput == "separate";
    } else {
        for (const char* flag : {"--interocular", "--convergence", "--stereo-output", "--anaglyph"})
            if (cmd.get_option(flag)->count() > 0) throw Error(std::string(flag) + " needs --stereo MODE");
    }
    if (!o.denoise.empty()) {
        DenoiseSettings d;
        d.method = parseDenoiseMethod(o.denoise);
        d.oidn.library = o.oidnLibrary;
        o.control.denoise = d;
        o.request.denoiseGuides = true;
    } else if (cmd.get_option("--oidn-library")->count() > 0) {
        throw Error("--oidn-library needs --denoise oidn");
    }
    if (o.control.resume && o.control.overwrite) throw Error("--resume and --overwrite exclude each other");
    o.request.defines = parseDefines(o.defines);
    o.request.accel = parseAccelKind(o.accel);
    o.request.embreeIsa = parseEmbreeIsa(o.embreeIsa);
    if (!o.res.empty()) {
        int w = 0, h = 0;
        char x = 0, extra = 0;
        if (std::sscanf(o.res.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
            throw Error("--res " + o.res + ": expected WIDTHxHEIGHT, e.g. 640x480");
        o.request.resolution = std::make_pair(w, h);
    }
}

}  // namespace caustica::cli
