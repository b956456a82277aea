// path_pass.cpp — the path tracer's pass driver for the device this file is compiled for (launch.h:
// g++ makes the CPU's; cuda/*_driver.cu includes this file so that nvcc makes the GPU's).
#include <memory>

#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/integrators/path/wavefront_pass.h"

namespace caustica {

/// The megakernel's estimator: the whole path in one work item (path_kernel.h).
struct PathRadiance {
    PathSettings settings;
    template <class Intersector, class Sampler>
    CA_HD Spectrum operator()(const SceneView& view, const Intersector& accel, Sampler& sampler, const Ray& ray,
                              uint32_t& rays) const {
        return pathRadiance(view, accel, sampler, ray, settings, rays);
    }
};

template <>
std::unique_ptr<PassDriver> makePathPass<DriverExec>(const Scene& scene, const Accel& accel,
                                                     const PathSettings& settings, PathMode mode,
                                                     size_t maxPathsInFlight) {
    if (mode == PathMode::Wavefront)
        return std::make_unique<WavefrontPass<DriverExec>>(scene, accel, settings, maxPathsInFlight);
    return std::make_unique<MegakernelPass<DriverExec, PathRadiance>>(scene, accel, PathRadiance{settings},
                                                                      "path.megakernel");
}

}  // namespace caustica
