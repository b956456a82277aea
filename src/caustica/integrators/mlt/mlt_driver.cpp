// mlt_driver.cpp — the MLT driver (mlt_driver.h) for the device this file is compiled for
// (launch.h: g++ makes the CPU's; cuda/*_driver.cu includes this file so that nvcc makes the GPU's).
#include "caustica/integrators/mlt/mlt_driver.h"

#include <algorithm>
#include <memory>

#include "caustica/integrators/mlt/mlt_gpu_memory.h"

namespace caustica {

template <>
std::unique_ptr<MltRenderer::Impl> makeMltDriver<DriverExec>(const Scene& scene, const Accel& accel,
                                                             const PathSettings& path, const MltSettings& settings,
                                                             uint64_t seed, Communicator& comm) {
    validateMltSettings(settings);
    if constexpr (DriverExec::kind == DeviceKind::Cpu) {
        if (settings.state == MltStateKind::Float)
            return std::make_unique<MltDriver<DriverExec, FloatChainStore>>(scene, accel, path, settings, seed, comm);
    } else {
        // Before any GPU work. Each path-tracing kernel holds a whole path tracer (minutes of
        // ptxas apiece): the GPU's are compiled for the compact state only.
        if (settings.state != MltStateKind::Compact)
            throw Error("--mlt-state float is not available on the GPU (its MLT kernels are compiled for the "
                        "compact state only); use --mlt-state compact or --device cpu");
        if (!accel.bvh()) throw Error("a GPU traces rays with caustica's own BVH, not Embree");
        MltSettings mine = settings;  // this rank's chains (mltShareOf)
        mine.chains = uint32_t(std::max<uint64_t>(1, mltShareOf(settings.chains, comm.rank(), comm.size()).count));
        checkGpuMltMemory(scene, *accel.bvh(), path, mine);
    }
    return std::make_unique<MltDriver<DriverExec, CompactChainStore>>(scene, accel, path, settings, seed, comm);
}

}  // namespace caustica
