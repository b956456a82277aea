// mlt_loop.h — runs a Metropolis render to a budget: bootstrap, then lock-step iterations until
// the wanted mutations per pixel or the time limit (bootstrap included) is reached.
#pragma once

#include <atomic>
#include <functional>

#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/render_loop.h"

namespace caustica {

struct MltBudget {
    double mutationsPerPixel = 0;  // proposals per pixel wanted; 0 = no limit
    double timeLimit = 0;          // seconds, bootstrap included; 0 = no limit
    const std::atomic<bool>* cancel = nullptr;
};

/// Called after every iteration with the running statistics (progress, periodic image writes).
using MltIterationFn = std::function<void(const MltRenderer& mlt, const RenderStats& stats)>;

/// Bootstraps `mlt` (unless it was loaded from a checkpoint) and iterates it until the budget is spent (at least one iteration). The
/// statistics count proposals as samples (RenderStats::samplesPerPixel: rounded mutations per pixel).
RenderStats runMlt(MltRenderer& mlt, const MltBudget& budget, const MltIterationFn& iterationDone = {});

}  // namespace caustica
