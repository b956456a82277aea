// caustica render SCENE — render a scene to image files, with a sample or time budget, progress,
// statistics and checkpoints.
#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "commands.h"
#include "render_mlt.h"
#include "render_output.h"
#include "caustica/accel/accel.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_integrator.h"
#include "caustica/integrators/render_loop.h"
#include "caustica/integrators/sample_pass.h"
#include "caustica/io/scene_loader.h"
#include "caustica/util/error.h"
#include "caustica/parallel/device_select.h"
#include "caustica/parallel/kernel_stats.h"
#include "caustica/util/progress.h"

#ifdef CAUSTICA_WITH_CUDA
#include "cuda/cuda_backend.h"
#include "cuda/gpu_mlt.h"
#include "cuda/gpu_path.h"
#endif

namespace caustica::cli {
namespace {

std::atomic<bool> gCancel{false};

void onInterrupt(int) {
    // First Ctrl-C: finish the pass, write the image and a checkpoint. Second: default action.
    gCancel.store(true);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

struct RenderOptions {
    std::string scene;
    std::vector<std::string> outputs;
    int spp = 0;
    double time = 0;
    int threads = 0;
    uint64_t seed = 0;
    std::string res;
    std::vector<std::string> defines;
    std::string accel = "embree";
    std::string integrator;  // empty: the scene's
    std::string pathMode = "megakernel";
    std::string device = "auto";
    std::string gpuMode = "megakernel";
    bool kernelStats = false;
    std::string statsJson;
    int sppPerPass = 0;
    double checkpointEvery = 60;
    bool resume = false;
    bool quiet = false;
    MltCliOptions mlt;
};

void applyResolution(Scene& scene, const std::string& res) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(res.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X'))
        throw Error("--res " + res + ": expected WIDTHxHEIGHT, e.g. 640x480");
    if (w <= 0 || h <= 0 || w > 32768 || h > 32768 || int64_t(w) * h > (int64_t(1) << 28))
        throw Error("--res " + res + ": absurd resolution (each side 1..32768, at most 2^28 pixels)");
    // Keeps the horizontal field of view (Mitsuba's default fov_axis="x").
    scene.camera.tanHalfY = scene.camera.tanHalfX * Float(h) / Float(w);
    scene.camera.width = scene.film.width = w;
    scene.camera.height = scene.film.height = h;
    scene.camera.cropX = scene.camera.cropY = 0;  // the whole image at the new size, no crop
}

}  // namespace

std::function<int()> addRenderCommand(CLI::App& app) {
    auto opt = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a Mitsuba 3 XML scene");
    cmd->add_option("scene", opt->scene, "Scene file (Mitsuba 3 XML)")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", opt->outputs,
                    "Output image(s): .exr (float RGB + metadata), .pfm, .png (sRGB); repeatable. "
                    "Default: SCENE_NAME.exr in the current directory");
    cmd->add_option("--spp", opt->spp, "Samples per pixel (default: the scene's sample_count; "
                                       "with --time alone: unlimited)")->check(CLI::Range(1, 1 << 24));
    cmd->add_option("--time", opt->time, "Time budget in seconds; stops after the pass that reaches it")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--threads", opt->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 4096));
    cmd->add_option("--seed", opt->seed, "Seed of the random streams (default: the scene sampler's "
                                         "seed); the image depends only on it, never on the thread count");
    cmd->add_option("--res", opt->res, "Override the film resolution, WIDTHxHEIGHT");
    cmd->add_option("-D,--define", opt->defines, "Set a scene <default> parameter: -D name=value (repeatable)");
    cmd->add_option("--accel", opt->accel, "Ray-tracing backend on the CPU (the GPU always traces the own BVH)")
        ->check(CLI::IsMember({"embree", "bvh"}));
    cmd->add_option("--integrator", opt->integrator, "Integrator (overrides the scene's)")
        ->check(CLI::IsMember({"path", "direct", "mlt"}));
    cmd->add_option("--path-mode", opt->pathMode,
                    "Path tracer execution on the CPU: megakernel (one work item per path) or "
                    "wavefront (one kernel per bounce stage); both give the same image")
        ->check(CLI::IsMember({"megakernel", "wavefront"}));
    cmd->add_option("--device", opt->device,
                    "Where to render: cpu, cuda, or auto (default: the GPU when this binary has "
                    "the CUDA backend and a GPU is present, else the CPU)")
        ->check(CLI::IsMember({"cpu", "cuda", "auto"}));
    cmd->add_option("--gpu-mode", opt->gpuMode,
                    "Path tracer execution on the GPU: megakernel (one thread per pixel sample) "
                    "or wavefront (one kernel per bounce stage over compacted queues)")
        ->check(CLI::IsMember({"megakernel", "wavefront"}));
    cmd->add_flag("--kernel-stats", opt->kernelStats,
                  "Time every named kernel launch and print the per-kernel table at the end");
    cmd->add_option("--stats-json", opt->statsJson, "Write the final statistics as JSON to this file");
    cmd->add_option("--spp-per-pass", opt->sppPerPass, "Samples per pixel in one pass (progress and "
                                                       "checkpoint granularity; default: about 256k samples a pass)")->check(CLI::Range(1, 4096));
    cmd->add_option("--checkpoint-every", opt->checkpointEvery,
                    "Seconds between checkpoints (images + OUTPUT.ckpt); 0 disables")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--resume", opt->resume, "Continue from OUTPUT.ckpt left by an interrupted render");
    cmd->add_flag("-q,--quiet", opt->quiet, "No progress bar");
    addMltOptions(*cmd, opt->mlt);

    CLI::Option* seedOption = cmd->get_option("--seed");
    return [opt, seedOption] {
        const bool seedGiven = seedOption->count() > 0;
        std::unique_ptr<tbb::global_control> threadLimit;
        if (opt->threads > 0)
            threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                size_t(opt->threads));
        // The device first: `--device cuda` without a GPU fails before any work is done.
        const DeviceKind device = selectDevice(opt->device, currentDeviceAvailability());
        bool onGpu = device == DeviceKind::Cuda;
        if (opt->kernelStats) {
            KernelStats::global().reset();
            KernelStats::global().setEnabled(true);
        }
        for (const std::string& out : opt->outputs) checkOutputPath(out);

        Scene scene = loadScene(opt->scene, parseDefines(opt->defines));
        if (opt->outputs.empty()) opt->outputs.push_back(defaultOutputPath(opt->scene, scene.film));
        if (!opt->res.empty()) applyResolution(scene, opt->res);
        if (!seedGiven) opt->seed = scene.seed;
        if (!opt->integrator.empty()) parseIntegratorType(opt->integrator, scene.integrator.type);
        const bool mlt = scene.integrator.type == IntegratorType::Mlt;
        if (!mlt && !rendersBySamplePasses(scene.integrator.type))
            throw Error(std::string("integrator ") + integratorTypeName(scene.integrator.type) +
                        " is not available in this build");
        // --device auto falls back to the CPU for what the GPU does not run: integrators other
        // than path and mlt, and mlt's float state (GPU kernels: compact state only).
        const bool gpuRuns = scene.integrator.type == IntegratorType::Path || (mlt && opt->mlt.state == "compact");
        if (onGpu && !gpuRuns && opt->device == "auto") onGpu = false;
        if (onGpu && mlt && !gpuRuns)
            throw Error("--mlt-state float is not available on the GPU (its MLT kernels are compiled for the "
                        "compact state only); use --mlt-state compact or --device cpu");
        if (onGpu && !mlt && scene.integrator.type != IntegratorType::Path)
            throw Error(std::string("--device cuda renders with the path and mlt integrators only; ") +
                        integratorTypeName(scene.integrator.type) + " runs on --device cpu");
        const int sppTarget = opt->spp > 0 ? opt->spp : (opt->time > 0 ? 0 : scene.sampleCount);

        Film film(scene.film);
        const std::string checkpoint = opt->outputs.front() + ".ckpt";
        if (opt->resume && !mlt) {  // an MLT render reads its own checkpoint (render_mlt.cpp)
            if (!std::filesystem::exists(checkpoint)) throw Error(checkpoint + ": no checkpoint to resume from");
            loadCheckpoint(checkpoint, film, opt->seed);
            std::fprintf(stderr, "resuming from %s at %d spp\n", checkpoint.c_str(), int(film.samplesPerPixel()));
        }

        // The GPU traces the own BVH; --accel chooses the CPU's backend.
        const AccelKind accelKind = onGpu ? AccelKind::Bvh : parseAccelKind(opt->accel);
        const std::string accelName = accelKindName(accelKind);
        auto buildStart = std::chrono::steady_clock::now();
        Accel accel(scene, accelKind);
        double buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();
        if (!opt->quiet)
            std::fprintf(stderr, "%s: %zu triangles, %zu spheres, %zu lights; %dx%d; %s built in %s\n",
                         opt->scene.c_str(), scene.triangles.size(), scene.spheres.size(), scene.lights.size(),
                         scene.film.width, scene.film.height, accelName.c_str(),
                         ProgressReporter::formatDuration(buildSeconds).c_str());

        if (mlt) {
            std::signal(SIGINT, onInterrupt);
            std::signal(SIGTERM, onInterrupt);
            MltRunRequest request;
            request.outputs = opt->outputs;
            request.mutationsPerPixel = opt->spp > 0 ? opt->spp : (opt->time > 0 ? 0 : scene.sampleCount);
            request.timeLimit = opt->time;
            request.checkpointEvery = opt->checkpointEvery;
            request.quiet = opt->quiet;
            request.statsJson = opt->statsJson;
            request.buildSeconds = buildSeconds;
            request.info = OutputInfo{opt->scene, "mlt", accelName, opt->seed, scene.film.tonemap};
            request.cancel = &gCancel;
            request.checkpoint = checkpoint;
            request.resume = opt->resume;
            MltSettings mltSettings =
                mltSettingsFrom(scene.integrator, opt->mlt, onGpu, uint64_t(scene.film.width) * uint64_t(scene.film.height));
            if (opt->resume && opt->mlt.chains == 0 && scene.integrator.mltChains == 0) {
                std::ifstream in(checkpoint, std::ios::binary);  // the drivers' defaults differ
                if (const uint32_t chains = mltCheckpointChains(in)) mltSettings.chains = chains;
            }
#ifdef CAUSTICA_WITH_CUDA
            if (onGpu) {  // the GPU driver (cuda/gpu_mlt.h), on the own BVH
                request.device = "cuda, " + cudaDeviceDescription();
                resetCudaPeakBytes();
                request.makeRenderer = [&scene, &accel, &mltSettings, seed = opt->seed] {
                    return makeGpuMltRenderer(scene, *accel.bvh(), pathSettingsFrom(scene.integrator), mltSettings,
                                              seed);
                };
            }
#endif
            const int code = runMltRender(scene, accel, mltSettings, opt->seed, request);
#ifdef CAUSTICA_WITH_CUDA
            if (onGpu) std::printf("GPU memory: peak %s allocated\n", formatBytes(cudaMemoryCounters().peak).c_str());
#endif
            if (opt->kernelStats)
                std::printf("kernel statistics (%s):\n%s", deviceName(onGpu ? DeviceKind::Cuda : DeviceKind::Cpu),
                            KernelStats::global().table().c_str());
            return code;
        }
        const PathSettings settings = pathSettingsFrom(scene.integrator);
        RenderBudget budget;
        budget.samplesPerPixel = sppTarget;
        budget.timeLimit = opt->time;
        const int pixels = scene.film.width * scene.film.height;
        budget.samplesPerPass = opt->sppPerPass > 0 ? opt->sppPerPass : std::clamp((1 << 18) / pixels, 1, 16);
        budget.cancel = &gCancel;

#ifdef CAUSTICA_WITH_CUDA
        std::unique_ptr<GpuPathRenderer> gpu;
        if (onGpu) {
            const GpuPathMode mode = parseGpuPathMode(opt->gpuMode);
            const GpuMemoryEstimate need =
                estimateGpuMemory(gpuRenderSizes(scene, *accel.bvh(), budget.samplesPerPass, mode));
            size_t freeBytes = 0, totalBytes = 0;
            cudaMemoryInfo(freeBytes, totalBytes);
            const std::string gpuName = cudaDeviceDescription();
            if (!opt->quiet) {
                std::fprintf(stderr, "device: cuda, %s; gpu-mode %s\n", gpuName.c_str(), gpuPathModeName(mode));
                std::fprintf(stderr,
                             "GPU memory needed: about %s (scene %s, BVH %s, path state %s for %zu paths, "
                             "sample pass %s, scratch %s); free %s of %s\n",
                             formatBytes(need.total()).c_str(), formatBytes(need.scene).c_str(),
                             formatBytes(need.bvh).c_str(), formatBytes(need.pathState).c_str(),
                             need.pathsInFlight, formatBytes(need.samplePass).c_str(),
                             formatBytes(need.scratch).c_str(), formatBytes(freeBytes).c_str(),
                             formatBytes(totalBytes).c_str());
            }
            if (need.total() > freeBytes)
                throw Error("GPU memory: the render needs about " + formatBytes(need.total()) + " but only " +
                            formatBytes(freeBytes) + " is free on " + gpuName +
                            "; lower --res or --spp-per-pass, or use --device cpu");
            resetCudaPeakBytes();
            gpu = std::make_unique<GpuPathRenderer>(scene, *accel.bvh(), settings, mode, budget.samplesPerPass);
        }
#endif
        if (!onGpu && !opt->quiet)
            std::fprintf(stderr, "device: cpu; path-mode %s\n", opt->pathMode.c_str());
        std::signal(SIGINT, onInterrupt);
        std::signal(SIGTERM, onInterrupt);

        std::unique_ptr<ProgressReporter> progress;
        if (!opt->quiet)
            progress = std::make_unique<ProgressReporter>("render", sppTarget > 0 ? sppTarget : 0, opt->time);
        double lastCheckpoint = 0;
        OutputInfo info{opt->scene, integratorTypeName(scene.integrator.type), accelName, opt->seed,
                        scene.film.tonemap};
        auto passDone = [&](const Film& f, const RenderStats& stats) {
            if (progress) progress->update(double(f.samplesPerPixel()));
            if (opt->checkpointEvery > 0 && stats.seconds - lastCheckpoint >= opt->checkpointEvery) {
                lastCheckpoint = stats.seconds;
                writeOutputs(opt->outputs, f, stats, info);
                saveCheckpoint(checkpoint, f, opt->seed);
            }
        };
        const bool wavefront = opt->pathMode == "wavefront";
        auto renderPass = [&](int first, int k, SamplePass& pass) -> uint64_t {
#ifdef CAUSTICA_WITH_CUDA
            if (gpu) return gpu->renderPass(opt->seed, first, pass);
#endif
            return renderSamplePass(scene, accel, scene.integrator, opt->seed, first, pass, wavefront);
        };
        RenderStats stats = runRenderLoop(film, budget, renderPass, passDone);
        if (progress) progress->finish();

        writeOutputs(opt->outputs, film, stats, info);
        if (stats.cancelled) {
            saveCheckpoint(checkpoint, film, opt->seed);
            std::fprintf(stderr, "interrupted: wrote %d spp and %s (continue with --resume)\n",
                         int(film.samplesPerPixel()), checkpoint.c_str());
        } else if (std::filesystem::exists(checkpoint)) {
            std::filesystem::remove(checkpoint);
        }
        printSummary(stats, stdout);
#ifdef CAUSTICA_WITH_CUDA
        if (gpu) {
            gpu.reset();
            std::printf("GPU memory: peak %s allocated\n", formatBytes(cudaMemoryCounters().peak).c_str());
        }
#endif
        if (opt->kernelStats) std::printf("kernel statistics (%s):\n%s", deviceName(onGpu ? DeviceKind::Cuda : DeviceKind::Cpu),
                                          KernelStats::global().table().c_str());
        if (!opt->statsJson.empty()) writeStatsJson(opt->statsJson, stats, info, buildSeconds);
        return stats.cancelled ? 130 : 0;
    };
}

}  // namespace caustica::cli
