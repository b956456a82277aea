// sppm_settings.h — stochastic progressive photon mapping's settings from the scene's
// <integrator type="sppm"> and the command line's --sppm-* options, which set the same parameters:
//
// | parameter      | option          | meaning (default)                                             |
// |----------------|-----------------|---------------------------------------------------------------|
// | max_depth      |                 | longest path in segments, eye + photon part (-1: unbounded,   |
// |                |                 | capped at kSppmDepthCap = 64 segments per eye or photon path) |
// | rr_depth       |                 | Russian roulette from this depth on, eye and photon paths (5) |
// | hide_emitters  |                 | emitters seen directly by the camera render black (false)     |
// | photon_count   | --sppm-photons  | photon paths per iteration (2^17), 1 .. 2^30                  |
// | initial_radius | --sppm-radius   | initial gather radius, world units (0: from the scene, see    |
// |                |                 | sppmAutoRadius), >= 0                                         |
// | alpha          | --sppm-alpha    | fraction of new photons kept per iteration, in (0, 1] (2/3)   |
//
// The random streams come from the render's seed (--seed, or the scene's sampler seed).
#pragma once

#include <cstdint>
#include <vector>

#include "caustica/integrators/integrator_params.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// Segments an eye path or a photon path traces at most when max_depth is -1 (unbounded).
inline constexpr int kSppmDepthCap = 64;
/// Photon paths per iteration by default: 2^17 = 131072. About 2 per pixel of a 256x256 image, so
/// the eye pass (one camera path per pixel) stays a minor part of an iteration, and at the 2-core
/// CPU's rate (~1e5 photon paths/s) an iteration takes about a second, short enough for
/// checkpoints and progress; pbrt-v4's measurement in issue 18 used 65536.
inline constexpr uint64_t kSppmDefaultPhotons = uint64_t(1) << 17;
inline constexpr uint64_t kSppmMaxPhotons = uint64_t(1) << 30;

struct SppmSettings {
    PathSettings path;                        // max_depth, rr_depth, hide_emitters (path_settings.h)
    uint64_t photonCount = kSppmDefaultPhotons;
    Float initialRadius = 0;                  // 0: sppmAutoRadius(scene)
    Float alpha = Float(2) / Float(3);
};

/// Reads and checks the settings (errors name file:line or the option, and the reason).
SppmSettings readSppmSettings(IntegratorParams& params);
/// The command-line options of the table above.
const std::vector<IntegratorOption>& sppmOptions();
/// The initial radius when none is given: 3 pixel footprints at the scene's scale,
/// R0 = 3 * |diagonal of the scene's bounds| / max(width, height). (A camera seeing the whole
/// scene spans about its diagonal across the image; pbrt-v4's cornell-water run of issue 18,
/// radius 0.04 at 256x256, is 3.0 footprints of this kind.)
Float sppmAutoRadius(const Scene& scene);

}  // namespace caustica
