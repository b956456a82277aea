// integrator_session.h — what the render session (renderer.h) needs of an integrator: advance by
// one pass or iteration, develop, count, and carry its state in a checkpoint. One implementation
// per kind of driver: passes of pixel samples (path, direct: pass_session.cpp) and Markov chains
// (mlt: mlt_session.cpp). The registry (integrator_registry.h) makes them by name.
#pragma once

#include <cstdint>
#include <cstdio>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "caustica/film/image.h"
#include "caustica/render/render_identity.h"

namespace caustica {

struct SamplePass;
struct AovSamplePass;
struct AovLayout;

/// Counters of the current run (not of earlier runs of a resumed render).
struct SessionCounters {
    uint64_t samples = 0;         // camera samples (proposals for mlt)
    uint64_t rays = 0;            // closest-hit + shadow rays
    uint64_t invalidSamples = 0;  // NaN/Inf/negative samples dropped (whole render)
};

class IntegratorSession {
public:
    virtual ~IntegratorSession() = default;
    /// One pass of samples per pixel (at most `samplesLeft` per pixel when > 0) or one MLT step
    /// (the bootstrap first, then iterations).
    virtual void step(double samplesLeft) = 0;
    /// Samples (mutations for mlt) per pixel of the whole render so far.
    virtual double samplesPerPixel() const = 0;
    /// The integrator's own cap on samplesPerPixel() when the request gives no sample count
    /// (sppm/ppm: max_passes); 0: none (the scene's sample count applies).
    virtual uint64_t passLimit() const { return 0; }
    /// Whether develop() has an image yet (mlt: after its first iteration).
    virtual bool hasImage() const = 0;
    virtual Image develop() const = 0;
    virtual SessionCounters counters() const = 0;
    /// The integrator's parameters that change the image, for the checkpoint's identity.
    virtual RenderIdentity parameters() const = 0;
    /// The integrator's state, in its own self-checking format (inside the checkpoint envelope).
    virtual void save(std::ostream& out) const = 0;
    /// Restores a state written by save(); throws caustica::Error (state unchanged) on a misfit.
    virtual void load(std::istream& in) = 0;
    /// One line for the start of a render ("device: cpu; path-mode megakernel").
    virtual std::string description() const = 0;
    /// Collective over ranks (Renderer::stats calls it on every rank before the statistics are
    /// read): brings what printSummary() and statsJson() show up to the whole render's where a
    /// session sums it over the ranks only on demand (mlt's counters).
    virtual void gatherStatistics() {}
    /// Further summary lines and statistics JSON entries (key, JSON value) of the integrator.
    virtual void printSummary(std::FILE* out) const { (void)out; }
    virtual std::vector<std::pair<std::string, std::string>> statsJson() const { return {}; }
    /// Whether step() renders a pass of independent pixel samples (path, direct), which
    /// lastPass() then shows: the AOVs (aov_session.h) take exactly its camera samples, and the
    /// variance AOV its radiance.
    virtual bool rendersPixelPasses() const { return false; }
    virtual const SamplePass* lastPass() const { return nullptr; }
    /// Asks a session of pixel passes to write the AOVs of `layout` for its own camera rays with
    /// each step (traced once for the image and the AOVs); lastAovPass() then shows them. False
    /// where it cannot (the wavefront path tracer): the AOV session traces them itself.
    virtual bool shareFirstHits(const AovLayout& layout) { (void)layout; return false; }
    virtual const AovSamplePass* lastAovPass() const { return nullptr; }
    /// Sessions without pixel passes (mlt, sppm, ppm) that can make a batch estimate per step:
    /// an image of that step's contribution alone, whose spread over the steps gives the variance
    /// AOV by batch means (aov_session.h, docs/AOV.md). recordStepEstimates() turns them on (they
    /// cost a develop per step); after each later step lastStepEstimate() shows the step's, or
    /// null for a step that made none (mlt's bootstrap).
    virtual bool hasStepEstimates() const { return false; }
    virtual void recordStepEstimates() {}
    virtual const Image* lastStepEstimate() const { return nullptr; }
};

}  // namespace caustica
