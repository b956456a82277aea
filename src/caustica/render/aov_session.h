// aov_session.h — the AOVs of a render (aov_layers.h), for any integrator: after each step of the
// integrator's session the AOV pass (integrators/aov/aov_pass.h) traces camera samples and the
// N-channel AovFilm reconstructs them with the scene's filter.
//
// - path, direct, whitted (sessions that render passes of pixel samples): the pass's own kernel
//   writes the AOVs of its camera rays' first hits (the ray traced once for both; megakernel
//   drivers), else (the wavefront) the AOV pass traces exactly the pass's camera samples again
//   (same seed, sample indices, film positions and rays); the variance AOV takes the pass's
//   radiance samples (pixel_variance.h).
// - mlt, sppm, ppm: one AOV sample per pixel per step (sample indices 0, 1, ...), up to
//   kAovSamplesPerPixelCap; the variance AOV by batch means: each step's own estimate of the
//   image (IntegratorSession::lastStepEstimate) is one batch, the layer s² / n of the batches
//   (NaN with fewer than 2 batches; docs/AOV.md).
// Checkpoints carry the AOV state after the integrator's (Renderer::save/load).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "caustica/accel/accel.h"
#include "caustica/film/aov_film.h"
#include "caustica/film/aov_layers.h"
#include "caustica/film/pixel_variance.h"
#include "caustica/integrators/aov/aov_pass.h"
#include "caustica/render/integrator_session.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// AOV samples per pixel, at most, for integrators that render no pixel passes (one per step).
inline constexpr uint64_t kAovSamplesPerPixelCap = 64;

class AovSession {
public:
    /// Throws caustica::Error when `spec` asks for variance and `session` renders neither pixel
    /// passes nor step estimates (whose recording it turns on).
    /// Asks `session` to share its camera rays' first hits (IntegratorSession::shareFirstHits);
    /// where it cannot, the AOV pass traces the camera rays again.
    AovSession(const Scene& scene, const Accel& accel, Device device, uint64_t seed, AovSpec spec,
               IntegratorSession& session, const std::string& integrator);
    ~AovSession();

    /// The AOV samples of the step the session just made; `samplesBefore`: the session's samples
    /// per pixel before that step.
    void afterStep(const IntegratorSession& session, double samplesBefore);
    /// Every layer's channels, in the spec's order.
    AovImage develop() const;
    const AovSpec& spec() const { return spec_; }
    uint64_t rays() const { return rays_; }
    /// AOV samples per pixel so far.
    uint64_t samplesPerPixel() const;

    void save(std::ostream& out) const;
    /// Refuses (caustica::Error) a stream without this render's AOV state, or (path, direct) one
    /// whose AOV samples are not the loaded session's `sessionSamplesPerPixel`.
    void load(std::istream& in, double sessionSamplesPerPixel);

private:
    const Scene& scene_;
    AovSpec spec_;
    uint64_t seed_ = 0;
    bool pixelPasses_ = false;
    bool batchMeans_ = false;  // the variance of step estimates (no pixel passes)
    AovLayout layout_;
    bool sharedFirstHits_ = false;           // the session writes the AOVs of its own camera rays
    std::unique_ptr<AovPassDriver> driver_;  // null when only variance is asked for, or shared
    std::optional<AovFilm> film_;
    std::optional<PixelVariance> variance_;
    AovSamplePass pass_;
    uint64_t rays_ = 0;
};

}  // namespace caustica
