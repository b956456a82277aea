// whitted_pass.cpp — the Whitted integrator's pass driver for the device this file is compiled
// for (launch.h: g++ makes the CPU's; cuda/whitted_driver.cu includes this file for nvcc).
#include <memory>

#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/whitted/whitted_kernel.h"

namespace caustica {

template <>
std::unique_ptr<PassDriver> makeWhittedPass<DriverExec>(const Scene& scene, const Accel& accel,
                                                        const WhittedSettings& settings) {
    return std::make_unique<MegakernelPass<DriverExec, WhittedRadiance>>(
        scene, accel, WhittedRadiance{settings}, "whitted.megakernel");
}

}  // namespace caustica
