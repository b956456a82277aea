// render_run.h — the one loop that drives every render to its budget: the checkpoint rules
// (resume, overwrite), periodic checkpoints with images, Ctrl-C, the progress bar, the outputs.
// `caustica render` is a thin caller of it:
//
//     RunControl control{...};
//     std::optional<CheckpointHeader> resume = prepareRun(control);  // fails before rendering
//     Renderer renderer(std::move(scene), request, resume ? &*resume : nullptr);
//     RunResult result = runRender(renderer, control);
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "caustica/render/checkpoint_envelope.h"
#include "caustica/render/denoise.h"
#include "caustica/render/renderer.h"
#include "caustica/render/stereo_outputs.h"

namespace caustica {

struct RunControl {
    std::vector<std::string> outputs;  // images, written at every checkpoint and at the end
    std::string checkpoint;            // OUTPUT.ckpt; "" = none
    double checkpointEvery = 60;       // seconds of this run between checkpoints; 0 = none but the last
    bool resume = false;               // continue the render saved in `checkpoint`
    bool overwrite = false;            // start over although `checkpoint` exists
    std::string statsJson;             // "" = none
    bool quiet = false;                // no progress bar, no start lines
    bool catchInterrupts = true;       // Ctrl-C / SIGTERM finish the step and save (interrupt.h)
    const std::atomic<bool>* cancel = nullptr;  // also stops after the current step when set
    StereoOutputs stereo;              // a stereo render's EXR layout and anaglyph
    /// Denoise the final image into NAME.denoised.EXT beside every output (render_denoise.h); the
    /// request must then ask for the guides (RenderRequest::denoiseGuides).
    std::optional<DenoiseSettings> denoise;
    /// Called after every step with the render's progress (the Python module's progress callback
    /// and Ctrl-C check); an exception it throws ends the render and propagates to the caller.
    std::function<void(const RenderProgress&)> onStep;
};

struct RunResult {
    bool cancelled = false;
    std::vector<std::string> written;  // every file the run wrote last (images, checkpoint, statistics)
};

/// Checks, before anything is rendered, that every output can be written and that the checkpoint
/// rules hold: a `checkpoint` that exists needs `resume` (continue) or `overwrite` (start over);
/// `resume` needs one. Returns the checkpoint's header when resuming. Throws caustica::Error.
std::optional<CheckpointHeader> prepareRun(const RunControl& control);
/// The same for a render over the ranks of `comm`, collective: rank 0 checks (it alone writes)
/// and broadcasts the header; a refusal is every rank's (AgreedError, rank 0's message).
std::optional<CheckpointHeader> prepareRun(const RunControl& control, Communicator& comm);

/// Loads the checkpoint when resuming (a mismatch throws and leaves it untouched), renders until
/// the budget is spent or an interrupt, writes images (and a checkpoint every checkpointEvery
/// seconds), and at the end the images, the statistics JSON and, when interrupted, the
/// checkpoint. A finished render removes its checkpoint.
///
/// Collective over the renderer's ranks (Renderer::comm): every rank calls it. The ranks agree
/// after every step on stopping (the budget as rank 0's clock sees it; Ctrl-C or SIGTERM on any
/// rank; `cancel` on any) and on checkpoints, so they all step equally often; rank 0 alone prints
/// the progress and writes images, checkpoint and statistics (result.written is rank 0's list on
/// every rank).
RunResult runRender(Renderer& renderer, const RunControl& control);

}  // namespace caustica
