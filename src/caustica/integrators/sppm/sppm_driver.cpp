// sppm_driver.cpp — the SPPM driver (sppm_driver.h) for the device this file is compiled for
// (launch.h: g++ makes the CPU's; cuda/*_driver.cu includes this file so that nvcc makes the GPU's).
#include "caustica/integrators/sppm/sppm_driver.h"

#include <memory>
#include <string>

#include "caustica/util/error.h"

namespace caustica {

template <>
std::unique_ptr<SppmDriverBase> makeSppmDriver<DriverExec>(const Scene& scene, const Accel& accel,
                                                           const SppmSettings& settings, uint64_t seed) {
    if (!(settings.alpha > 0 && settings.alpha <= 1)) throw Error("sppm: alpha must be in (0, 1]");
    if (settings.photonCount == 0 || settings.photonCount > kSppmMaxPhotons)
        throw Error("sppm: photon_count must be in [1, 2^30]");
    if (!(settings.initialRadius >= 0)) throw Error("sppm: initial_radius must be >= 0");
    if constexpr (DriverExec::kind != DeviceKind::Cpu) {
        if (!accel.bvh()) throw Error("a GPU traces rays with caustica's own BVH, not Embree");
    }
    return std::make_unique<SppmDriver<DriverExec>>(scene, accel, settings, seed);
}

}  // namespace caustica
