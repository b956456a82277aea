#include "caustica/render/render_run.h"


#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "caustica/render/interrupt.h"
#include "caustica/render/render_denoise.h"
#include "caustica/render/render_outputs.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica {

namespace fs = std::filesystem;

std::optional<CheckpointHeader> prepareRun(const RunControl& c) {
    for (const std::string& out : c.outputs) checkImageOutputPath(out);
    checkStereoOutputFiles(c.outputs, c.stereo);
    if (c.denoise) checkDenoiseOutputs(c.outputs, *c.denoise, c.stereo);
    if (!c.statsJson.empty()) checkWritablePath(c.statsJson, "statistics");
    if (c.checkpoint.empty()) {
        if (c.resume) throw Error("--resume needs a checkpoint, and this render writes none");
        return std::nullopt;
    }
    checkWritablePath(c.checkpoint, "checkpoint");
    std::error_code ec;
    const bool exists = fs::exists(c.checkpoint, ec);
    if (c.resume) {
        if (!exists) throw Error(c.checkpoint + ": no checkpoint to resume from");
        return readCheckpointHeaderFile(c.checkpoint);
    }
    if (exists && !c.overwrite)
        throw Error(c.checkpoint + ": a checkpoint of an unfinished render exists; pass --resume to continue it or "
                    "--overwrite to start over");
    return std::nullopt;
}

RunResult runRender(Renderer& renderer, const RunControl& c) {
    if (c.resume) {
        renderer.load(c.checkpoint);
        std::fprintf(stderr, "resuming from %s at %.4g spp after %s\n", c.checkpoint.c_str(),
                         renderer.progress().samplesPerPixel,
                         ProgressReporter::formatDuration(renderer.progress().seconds).c_str());
    }
    std::unique_ptr<InterruptGuard> interrupts;
    if (c.catchInterrupts) interrupts = std::make_unique<InterruptGuard>(c.checkpoint);
    auto cancelled = [&] {
        return (c.cancel && c.cancel->load()) || (interrupts && InterruptGuard::requested().load());
    };
    std::unique_ptr<ProgressReporter> progress;
    if (!c.quiet) {
        const RenderProgress p = renderer.progress();
        progress = std::make_unique<ProgressReporter>("render", p.target,
                                                      p.timeLimit > 0 ? std::max(p.timeLimit - p.seconds, 1e-3) : 0);
    }
    RunResult result;
    auto saveCheckpoint = [&] {
        if (!c.checkpoint.empty()) renderer.save(c.checkpoint);
    };
    double lastCheckpoint = renderer.runSeconds();
    while (!renderer.finished()) {
        if (cancelled()) {
            result.cancelled = true;
            break;
        }
        renderer.step();
        if (progress) progress->update(renderer.progress().samplesPerPixel);
        if (c.checkpointEvery > 0 && renderer.runSeconds() - lastCheckpoint >= c.checkpointEvery &&
            !renderer.finished()) {
            lastCheckpoint = renderer.runSeconds();
            writeRenderImages(c.outputs, renderer.develop(), renderer, c.stereo);
            saveCheckpoint();
        }
    }
    if (progress) progress->finish();

    // A render interrupted before its integrator had an image (MLT's bootstrap) saves its state
    // but writes no image.
    if (renderer.session().hasImage()) {
        const Image image = renderer.develop();
        writeRenderImages(c.outputs, image, renderer, c.stereo);
        result.written = stereoOutputFiles(c.outputs, c.stereo);
        // Only the final image is denoised (not every checkpoint's: the filter costs seconds).
        if (c.denoise)
            for (std::string& p : writeDenoisedImages(c.outputs, image, renderer, *c.denoise, c.stereo))
                result.written.push_back(std::move(p));
    }
    if (result.cancelled) {
        saveCheckpoint();
        if (!c.checkpoint.empty()) result.written.push_back(c.checkpoint);
        std::fprintf(stderr, "interrupted at %.4g spp: continue with --resume (checkpoint %s)\n",
                     renderer.progress().samplesPerPixel, c.checkpoint.empty() ? "none" : c.checkpoint.c_str());
    } else if (!c.checkpoint.empty()) {
        std::error_code ec;
        fs::remove(c.checkpoint, ec);  // the render is complete: nothing left to resume
    }
    if (!c.statsJson.empty()) {
        writeRenderStatsJson(c.statsJson, renderer, result.cancelled);
        result.written.push_back(c.statsJson);
    }
    return result;
}

}  // namespace caustica
