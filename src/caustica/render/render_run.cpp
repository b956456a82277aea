#include "caustica/render/render_run.h"


#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "caustica/distributed/agreed_error.h"
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

std::optional<CheckpointHeader> prepareRun(const RunControl& control, Communicator& comm) {
    if (comm.size() == 1) return prepareRun(control);
    std::optional<CheckpointHeader> header;
    agreeOnFailure(comm, [&] {
        if (comm.isRoot()) header = prepareRun(control);
    });
    std::vector<uint8_t> bytes;  // empty: no resume; else the header as the checkpoint holds it
    if (comm.isRoot() && header) {
        std::ostringstream out(std::ios::binary);
        writeCheckpointHeader(out, *header);
        const std::string text = out.str();
        bytes.assign(text.begin(), text.end());
    }
    comm.broadcast(bytes, 0);
    if (bytes.empty()) return std::nullopt;
    std::istringstream in(std::string(bytes.begin(), bytes.end()), std::ios::binary);
    return readCheckpointHeader(in);
}

namespace {

/// What the ranks agree on before each step.
struct StepDecision {
    bool finished = false, cancelled = false, checkpointDue = false;
};

/// Rank 0's view of the budget and of the checkpoint clock (so every rank stops after the same
/// step), any rank's interrupt. One small sum over the ranks; nothing for a single process.
StepDecision agreeOnStep(Communicator& comm, bool finished, bool cancelled, bool checkpointDue) {
    double flags[3] = {cancelled ? 1.0 : 0.0, comm.isRoot() && finished ? 1.0 : 0.0,
                       comm.isRoot() && checkpointDue ? 1.0 : 0.0};
    comm.sum(std::span<double>(flags));
    return StepDecision{flags[1] > 0, flags[0] > 0, flags[2] > 0};
}

}  // namespace

RunResult runRender(Renderer& renderer, const RunControl& c) {
    Communicator& comm = renderer.comm();
    const bool root = comm.isRoot();
    if (c.resume) {
        renderer.load(c.checkpoint);
        if (root)
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
    if (!c.quiet && root) {
        const RenderProgress p = renderer.progress();
        progress = std::make_unique<ProgressReporter>("render", p.target,
                                                      p.timeLimit > 0 ? std::max(p.timeLimit - p.seconds, 1e-3) : 0);
    }
    RunResult result;
    auto saveCheckpoint = [&] {
        if (!c.checkpoint.empty()) renderer.save(c.checkpoint);  // collective
    };
    // Images are rank 0's to write, but develop() may be collective (a session's choice): all call it.
    auto writeImages = [&](const Image& image) {
        agreeOnFailure(comm, [&] {
            if (root) writeRenderImages(c.outputs, image, renderer, c.stereo);
        });
    };
    double lastCheckpoint = renderer.runSeconds();
    bool stepped = false;
    for (;;) {
        const StepDecision d = agreeOnStep(
            comm, renderer.finished(), cancelled(),
            stepped && c.checkpointEvery > 0 && renderer.runSeconds() - lastCheckpoint >= c.checkpointEvery);
        if (d.finished) break;
        if (d.cancelled) {
            result.cancelled = true;
            break;
        }
        if (d.checkpointDue) {
            lastCheckpoint = renderer.runSeconds();
            writeImages(renderer.develop());
            saveCheckpoint();
        }
        renderer.step();
        stepped = true;
        if (progress) progress->update(renderer.progress().samplesPerPixel);
        if (c.onStep) c.onStep(renderer.progress());
    }
    if (progress) progress->finish();

    // A render interrupted before its integrator had an image (MLT's bootstrap) saves its state
    // but writes no image.
    if (renderer.session().hasImage()) {
        const Image image = renderer.develop();
        writeImages(image);
        result.written = stereoOutputFiles(c.outputs, c.stereo);
        // Only the final image is denoised (not every checkpoint's: the filter costs seconds).
        // (A render over several ranks has no denoiser guides: Renderer refuses them.)
        if (c.denoise && root)
            for (std::string& p : writeDenoisedImages(c.outputs, image, renderer, *c.denoise, c.stereo))
                result.written.push_back(std::move(p));
    }
    if (result.cancelled) {
        saveCheckpoint();
        if (!c.checkpoint.empty()) result.written.push_back(c.checkpoint);
        if (root && c.catchInterrupts)  // the loop handled Ctrl-C: say how to go on (a library caller knows)
            std::fprintf(stderr, "interrupted at %.4g spp: continue with --resume (checkpoint %s)\n",
                         renderer.progress().samplesPerPixel, c.checkpoint.empty() ? "none" : c.checkpoint.c_str());
    } else if (!c.checkpoint.empty() && root) {
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
