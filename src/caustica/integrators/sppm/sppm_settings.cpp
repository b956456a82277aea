#include "caustica/integrators/sppm/sppm_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "caustica/integrators/path/path_settings.h"

namespace caustica {

SppmSettings readSppmSettings(IntegratorParams& p, PhotonMapper mapper) {
    SppmSettings s;
    s.mapper = mapper;
    s.path = readPathSettings(p);
    // Default: albedo, pbrt-v4's and Jensen's photon roulette: 1.15-1.3x lower error than the path
    // tracer's rule in 10-20 s on cornell-water and cornell-box (equal within noise in 60 s), 0.75x
    // the time per iteration and less memory (docs/SPPM.md, "Photon roulette").
    s.photonRoulette = p.getString("photon_roulette", "albedo", {"albedo", "throughput"}) == "throughput"
                           ? PhotonRoulette::Throughput
                           : PhotonRoulette::Albedo;
    s.photonCount = uint64_t(p.getInt("photon_count", int64_t(kSppmDefaultPhotons), 1, int64_t(kSppmMaxPhotons),
                                      "must be a whole number of photons in [1, 2^30]"));
    const double radius = p.getFloat("initial_radius", 0, -1e30, 1e30);
    if (radius < 0) p.fail("initial_radius", "must be >= 0 (0: from the pixel footprint)");
    s.initialRadius = Float(radius);
    const double alpha = p.getFloat("alpha", 2.0 / 3.0, -1e30, 1e30);
    if (!(alpha > 0 && alpha <= 1)) p.fail("alpha", "must be in (0, 1]");
    s.alpha = Float(alpha);
    s.radiusSchedule = p.getString("radius_schedule", "local", {"local", "global"}) == "global"
                           ? RadiusSchedule::Global
                           : RadiusSchedule::Local;
    const double rough = p.getFloat("roughness_threshold", 0, -1e30, 1e30);
    if (!(rough >= 0 && rough <= 1)) p.fail("roughness_threshold", "must be in [0, 1] (a microfacet alpha)");
    s.roughnessThreshold = Float(rough);
    s.maxPasses = uint64_t(p.getInt("max_passes", 0, 0, int64_t(1) << 40, "must be >= 0 (0: the sample count)"));
    // Default: the uniform grid, the fastest measured (docs/PHOTON_LOOKUP.md, "Measurements").
    const std::string structure = p.getString("structure", "grid", {"hash", "grid", "kdtree", "multihash", "brute"});
    s.structure = structure == "hash"        ? PhotonStructure::Hash
                  : structure == "kdtree"    ? PhotonStructure::KdTree
                  : structure == "multihash" ? PhotonStructure::MultiHash
                  : structure == "brute"     ? PhotonStructure::Brute
                                             : PhotonStructure::Grid;
    // Default: auto, gather or deposit by the scene (sppm_direction.h; docs/SPPM.md, "Direction").
    const std::string direction = p.getString("direction", "auto", {"auto", "deposit", "gather"});
    s.direction = direction == "deposit"  ? PhotonDirection::Deposit
                  : direction == "gather" ? PhotonDirection::Gather
                                          : PhotonDirection::Auto;
    const std::string order = p.getString("hitpoint_order", "morton", {"morton", "kmeans", "none"});
    s.hitpointOrder = order == "kmeans" ? HitpointOrder::Kmeans : order == "none" ? HitpointOrder::None : HitpointOrder::Morton;
    s.sortPhotons = p.getBool("sort_photons", true);
    s.seed = p.getInt("seed", -1, -1, INT64_MAX, "must be a whole number >= 0 (or -1: the render's seed)");
    if (mapper == PhotonMapper::Ppm)
        s.hitpoints = uint32_t(p.getInt("hitpoints", 1, 1, kPpmMaxHitpoints, "must be in [1, 256]"));
    return s;
}

namespace {
std::vector<IntegratorOption> commonOptions() {
    return {
        {"--sppm-photons", "photon_count", "photon mapping: photon paths per iteration, 1..2^30 (default 2^17)"},
        {"--sppm-radius", "initial_radius",
         "photon mapping: initial gather radius in world units, >= 0 (default 0: 3 pixel footprints at the "
         "median distance of the visible points)"},
        {"--sppm-roulette", "photon_roulette",
         "photon mapping: photon paths' roulette, albedo (every bounce, photons keep their power) or throughput "
         "(the path tracer's rule from rr_depth on) (default albedo)"},
        {"--sppm-alpha", "alpha", "photon mapping: fraction of the new photons kept per iteration, in (0, 1] (default 2/3)"},
        {"--sppm-schedule", "radius_schedule",
         "photon mapping: radius reduction, local (per pixel) or global (one radius per iteration) (default local)"},
        {"--sppm-roughness", "roughness_threshold",
         "photon mapping: microfacet lobes with alpha below this are specular (default 0: delta only)"},
        {"--sppm-passes", "max_passes", "photon mapping: iterations when --spp is not given (default: the sample count)"},
        {"--sppm-structure", "structure", "photon mapping: lookup structure, hash, grid, kdtree, multihash or brute (default grid)"},
        {"--sppm-direction", "direction",
         "photon mapping: deposit (photons into visible points' spheres), gather (stored photons) or auto (the "
         "faster on the scene: gather when a pilot finds many photons per visible point, else two passes of each timed) "
         "(default auto)"},
        {"--sppm-order", "hitpoint_order",
         "photon mapping: order of the visible points, morton, kmeans (clusters, seed 003) or none (default morton)"},
        {"--sppm-sort-photons", "sort_photons",
         "photon mapping, gather: photons copied into cell order, true/false (default true)"},
    };
}
}  // namespace

const std::vector<IntegratorOption>& sppmOptions() {
    static const std::vector<IntegratorOption> options = commonOptions();
    return options;
}

const std::vector<IntegratorOption>& ppmOptions() {
    static const std::vector<IntegratorOption> options = [] {
        std::vector<IntegratorOption> o = commonOptions();
        o.push_back({"--ppm-hitpoints", "hitpoints", "PPM: hitpoints per pixel of the one eye pass, 1..256 (default 1)"});
        return o;
    }();
    return options;
}

Float sppmAutoRadius(const Scene& scene) {
    const Bounds3f b = scene.bounds();
    const double diagonal = b.empty() ? 1.0 : double(length(b.diagonal()));
    // One eye's width on a stereo rig (the film holds both side by side).
    const int width = scene.camera.eyeWidth > 0 ? scene.camera.eyeWidth : scene.film.width;
    const double pixels = double(std::max({width, scene.film.height, 1}));
    const double r = 3.0 * (diagonal > 0 ? diagonal : 1.0) / pixels;
    return Float(r);
}

const char* radiusScheduleName(RadiusSchedule s) { return s == RadiusSchedule::Global ? "global" : "local"; }
const char* photonStructureName(PhotonStructure s) {
    return s == PhotonStructure::Grid        ? "grid"
           : s == PhotonStructure::KdTree    ? "kdtree"
           : s == PhotonStructure::MultiHash ? "multihash"
           : s == PhotonStructure::Brute     ? "brute"
                                             : "hash";
}
const char* photonDirectionName(PhotonDirection d) {
    return d == PhotonDirection::Gather ? "gather" : d == PhotonDirection::Deposit ? "deposit" : "auto";
}
const char* photonRouletteName(PhotonRoulette r) {
    return r == PhotonRoulette::Throughput ? "throughput" : "albedo";
}
const char* hitpointOrderName(HitpointOrder o) {
    return o == HitpointOrder::Kmeans ? "kmeans" : o == HitpointOrder::None ? "none" : "morton";
}

}  // namespace caustica
