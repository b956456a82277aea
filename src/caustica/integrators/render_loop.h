// render_loop.h — the progressive driver shared by the integrators: runs passes of samples into a
// film until a sample count or a time budget is reached, reports progress, and lets the caller
// checkpoint between passes. Integrator-specific work is the `renderPass` callback.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "caustica/film/film.h"

namespace caustica {

struct RenderBudget {
    int samplesPerPixel = 0;   // total spp wanted (counting samples already in a resumed film); 0 = no limit
    double timeLimit = 0;      // seconds of rendering in this run; 0 = no limit
    int samplesPerPass = 1;    // samples per pixel in one pass
    const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop after the current pass
};

struct RenderStats {
    double seconds = 0;          // wall time of this run
    uint64_t samples = 0;        // camera samples taken in this run
    uint64_t rays = 0;           // rays traced in this run (closest hit + shadow)
    int samplesPerPixel = 0;     // total spp in the film at the end (including resumed ones)
    uint64_t invalidSamples = 0; // NaN/Inf/negative samples dropped (whole film)
    bool cancelled = false;
};

/// Renders one pass: fills `pass` with `samplesPerPass` samples per pixel whose sample indices
/// start at `firstSampleIndex`; returns the number of rays traced.
using RenderPassFn = std::function<uint64_t(int firstSampleIndex, int samplesPerPass, SamplePass& pass)>;
/// Called after each pass with the running statistics (progress, checkpoints).
using PassDoneFn = std::function<void(const Film& film, const RenderStats& stats)>;

RenderStats runRenderLoop(Film& film, const RenderBudget& budget, const RenderPassFn& renderPass,
                          const PassDoneFn& passDone = {});

}  // namespace caustica
