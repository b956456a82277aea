// render_mlt.h — `caustica render` with the Metropolis integrator: its options and its run.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "render_output.h"
#include "caustica/accel/accel.h"
#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/scene/scene.h"

namespace caustica::cli {

/// --mlt-* options; unset ones (0, empty, negative) take the scene's <integrator type="mlt">
/// parameters, then the renderer's defaults.
struct MltCliOptions {
    uint32_t chains = 0;
    uint64_t bootstrap = 0;
    double largeStep = -1;
    uint32_t proposals = 0;
    double s1 = -1, s2 = -1;
    std::string state = "compact", splat = "atomic", start = "bootstrap", target;  // target "": the scene's
    uint32_t sortEvery = 0;
};

void addMltOptions(CLI::App& cmd, MltCliOptions& options);
/// The MLT settings of a render: the command line's over the scene's over the defaults (the chain
/// count's depends on the device and the image size: mltDefaultChains).
MltSettings mltSettingsFrom(const IntegratorDesc& desc, const MltCliOptions& options, bool gpu, uint64_t pixels);

struct MltRunRequest {
    std::vector<std::string> outputs;
    double mutationsPerPixel = 0, timeLimit = 0, checkpointEvery = 0;
    bool quiet = false;
    std::string statsJson;
    double buildSeconds = 0;
    OutputInfo info;
    const std::atomic<bool>* cancel = nullptr;
    /// The driver to run (the GPU's: cuda/gpu_mlt.h); unset: the CPU driver over `accel`.
    std::function<std::unique_ptr<MltRenderer>()> makeRenderer;
    std::string device = "cpu";  // printed as "device: <device>" ("cuda, <GPU name>")
    /// Resumable checkpoint (OUTPUT.ckpt): written with the images every checkpointEvery seconds
    /// and on an interruption, read first with `resume`, removed after a finished render.
    std::string checkpoint;
    bool resume = false;
};

/// Renders with MLT, writes the outputs (also every checkpointEvery seconds), prints the summary
/// and the Metropolis statistics. Returns the process exit code.
int runMltRender(const Scene& scene, const Accel& accel, const MltSettings& settings, uint64_t seed,
                 const MltRunRequest& request);

}  // namespace caustica::cli
