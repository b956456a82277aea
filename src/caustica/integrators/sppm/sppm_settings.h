// sppm_settings.h — the photon mappers' settings (integrators `sppm` and `ppm`) from the scene's
// <integrator type="sppm"|"ppm"> and the command line's --sppm-* options, which set the same
// parameters:
//
// | parameter          | option                | meaning (default)                                     |
// |--------------------|-----------------------|-------------------------------------------------------|
// | max_depth          |                       | longest path in segments, eye + photon part (-1:      |
// |                    |                       | unbounded, capped at kSppmDepthCap per part)          |
// | rr_depth           |                       | Russian roulette from this depth on (5): eye paths,   |
// |                    |                       | and photon paths with photon_roulette = throughput    |
// | photon_roulette    | --sppm-roulette       | albedo: at every bounce a photon goes on with the     |
// |                    |                       | bounce's albedo and keeps its power; throughput: the  |
// |                    |                       | path tracer's rule from rr_depth on (albedo)          |
// | hide_emitters      |                       | emitters seen directly render black (false)           |
// | photon_count       | --sppm-photons        | photon paths per iteration (2^17), 1 .. 2^30          |
// | initial_radius     | --sppm-radius         | initial gather radius, world units, >= 0 (0: 3 pixel  |
// |                    |                       | footprints at the median visible-point distance)      |
// | alpha              | --sppm-alpha          | fraction of new photons kept, in (0, 1] (2/3)         |
// | radius_schedule    | --sppm-schedule       | local (per pixel, Hachisuka & Jensen) or global       |
// |                    |                       | (one radius per iteration, Knaus & Zwicker) (local)   |
// | roughness_threshold| --sppm-roughness      | microfacet lobes with alpha below it count as         |
// |                    |                       | specular: no visible point, no deposit (0: delta only)|
// | max_passes         | --sppm-passes         | iterations when --spp is not given (0: the sampler's  |
// |                    |                       | sample_count)                                         |
// | structure          | --sppm-structure      | hash, grid, kdtree, multihash or brute (grid)         |
// | direction          | --sppm-direction      | deposit: photons add into the visible points' spheres |
// |                    |                       | (no photon storage); gather: photons are stored and   |
// |                    |                       | each visible point gathers them; auto: the faster one |
// |                    |                       | on this scene (sppm_direction.h) (auto)               |
// | hitpoint_order     | --sppm-order          | visible points in morton order, kmeans clusters (seed |
// |                    |                       | 003) or none (morton)                                 |
// | sort_photons       | --sppm-sort-photons   | gather: photons copied into cell order (true)         |
// | hitpoints          | --ppm-hitpoints       | ppm: hitpoints per pixel of its one eye pass (1)      |
// | seed               |                       | seed of the random streams (-1: the render's)         |
//
// The random streams come from --seed when given, else the integrator's `seed`, else the scene's
// sampler seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "caustica/integrators/integrator_params.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// Segments an eye path or a photon path traces at most when max_depth is -1 (unbounded).
inline constexpr int kSppmDepthCap = 64;
/// Photon paths per iteration by default: 2^17 = 131072. About 2 per pixel of a 256x256 image, so
/// the eye pass (one camera path per pixel) stays a minor part of an iteration, and an iteration
/// takes well under a second on a 2-core CPU, short enough for checkpoints and progress;
/// pbrt-v4's measurement in issue 18 used 65536.
inline constexpr uint64_t kSppmDefaultPhotons = uint64_t(1) << 17;
inline constexpr uint64_t kSppmMaxPhotons = uint64_t(1) << 30;
inline constexpr uint32_t kPpmMaxHitpoints = 256;

enum class PhotonMapper { Sppm, Ppm };
enum class RadiusSchedule { Local, Global };
enum class PhotonStructure { Hash, Grid, KdTree, MultiHash, Brute };
enum class PhotonDirection { Deposit, Gather, Auto };  // Auto: sppm_direction.h
enum class HitpointOrder { None, Morton, Kmeans };  // sppm_order.h
/// How a photon path decides whether it goes on after a bounce (sppmPhotonSurvival, sppm_photon.h).
enum class PhotonRoulette : uint8_t {
    Albedo,      // every bounce: survival = the bounce's throughput ratio (<= 1), photons keep their power
    Throughput,  // from rr_depth on: survival = min(throughput, 0.95), the path tracer's rule
};

struct SppmSettings {
    PhotonMapper mapper = PhotonMapper::Sppm;
    PathSettings path;                        // max_depth, rr_depth, hide_emitters (path_settings.h)
    PhotonRoulette photonRoulette = PhotonRoulette::Albedo;
    uint64_t photonCount = kSppmDefaultPhotons;
    Float initialRadius = 0;                  // 0: sppmAutoRadius(scene)
    Float alpha = Float(2) / Float(3);
    RadiusSchedule radiusSchedule = RadiusSchedule::Local;
    Float roughnessThreshold = 0;
    uint64_t maxPasses = 0;                   // 0: the sampler's sample_count
    PhotonStructure structure = PhotonStructure::Grid;
    PhotonDirection direction = PhotonDirection::Auto;
    HitpointOrder hitpointOrder = HitpointOrder::Morton;
    bool sortPhotons = true;
    uint32_t hitpoints = 1;                   // ppm only
    int64_t seed = -1;                        // -1: the render's seed
};

/// Reads and checks the settings of `mapper` (errors name file:line or the option, and the reason).
SppmSettings readSppmSettings(IntegratorParams& params, PhotonMapper mapper = PhotonMapper::Sppm);
/// The command-line options of the table above (sppm: all but --ppm-hitpoints; ppm: all).
const std::vector<IntegratorOption>& sppmOptions();
const std::vector<IntegratorOption>& ppmOptions();
/// The auto initial radius in pixel footprints at the median distance of the visible points.
inline constexpr Float kSppmAutoFootprints = 3;
/// The initial radius when none is given and no visible point shows the scene's depth: 3 pixel
/// footprints at the scene's scale,
/// R0 = 3 * |diagonal of the scene's bounds| / max(width, height). (A camera seeing the whole
/// scene spans about its diagonal across the image; pbrt-v4's cornell-water run of issue 18,
/// radius 0.04 at 256x256, is 3.0 footprints of this kind.)
Float sppmAutoRadius(const Scene& scene);

const char* radiusScheduleName(RadiusSchedule s);
const char* photonStructureName(PhotonStructure s);
const char* photonDirectionName(PhotonDirection d);
const char* hitpointOrderName(HitpointOrder o);
const char* photonRouletteName(PhotonRoulette r);

}  // namespace caustica
