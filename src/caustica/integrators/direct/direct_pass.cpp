// direct_pass.cpp — the direct-lighting integrator's pass driver for the device this file is
// compiled for (launch.h: g++ makes the CPU's; cuda/*_driver.cu includes this file for nvcc).
#include <memory>

#include "caustica/integrators/direct/direct_kernel.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/pass_driver.h"

namespace caustica {

/// Emitters seen directly or after one scattering event (direct_kernel.h).
struct DirectRadiance {
    DirectSettings settings;
    template <class Intersector, class Sampler>
    CA_HD Spectrum operator()(const SceneView& view, const Intersector& accel, Sampler& sampler, const Ray& ray,
                              uint32_t& rays) const {
        return directRadiance(view, accel, sampler, ray, settings, rays);
    }
};

template <>
std::unique_ptr<PassDriver> makeDirectPass<DriverExec>(const Scene& scene, const Accel& accel,
                                                       const DirectSettings& settings) {
    return std::make_unique<MegakernelPass<DriverExec, DirectRadiance>>(scene, accel, DirectRadiance{settings},
                                                                        "direct.megakernel");
}

}  // namespace caustica
