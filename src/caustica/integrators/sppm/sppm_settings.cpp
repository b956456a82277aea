#include "caustica/integrators/sppm/sppm_settings.h"

#include <algorithm>
#include <cmath>

#include "caustica/integrators/path/path_settings.h"

namespace caustica {

SppmSettings readSppmSettings(IntegratorParams& p) {
    SppmSettings s;
    s.path = readPathSettings(p);
    s.photonCount = uint64_t(p.getInt("photon_count", int64_t(kSppmDefaultPhotons), 1, int64_t(kSppmMaxPhotons),
                                      "must be a whole number of photons in [1, 2^30]"));
    const double radius = p.getFloat("initial_radius", 0, -1e30, 1e30);
    if (radius < 0) p.fail("initial_radius", "must be >= 0 (0: from the scene's size and resolution)");
    s.initialRadius = Float(radius);
    const double alpha = p.getFloat("alpha", 2.0 / 3.0, -1e30, 1e30);
    if (!(alpha > 0 && alpha <= 1)) p.fail("alpha", "must be in (0, 1]");
    s.alpha = Float(alpha);
    return s;
}

const std::vector<IntegratorOption>& sppmOptions() {
    static const std::vector<IntegratorOption> options = {
        {"--sppm-photons", "photon_count", "SPPM: photon paths per iteration, 1..2^30 (default 2^17)"},
        {"--sppm-radius", "initial_radius",
         "SPPM: initial gather radius in world units, >= 0 (default 0: 3 x scene diagonal / image size)"},
        {"--sppm-alpha", "alpha", "SPPM: fraction of the new photons kept per iteration, in (0, 1] (default 2/3)"},
    };
    return options;
}

Float sppmAutoRadius(const Scene& scene) {
    const Bounds3f b = scene.bounds();
    const double diagonal = b.empty() ? 1.0 : double(length(b.diagonal()));
    const double pixels = double(std::max({scene.film.width, scene.film.height, 1}));
    const double r = 3.0 * (diagonal > 0 ? diagonal : 1.0) / pixels;
    return Float(r);
}

}  // namespace caustica
