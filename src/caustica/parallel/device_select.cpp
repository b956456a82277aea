#include "caustica/parallel/device_select.h"

#include "caustica/parallel/backend.h"
#include "caustica/util/error.h"

namespace caustica {

DeviceAvailability currentDeviceAvailability() {
    DeviceAvailability a;
    a.cudaBackend = gpuBackend() != nullptr;
    a.gpuCount = a.cudaBackend ? gpuDeviceCount() : 0;
    return a;
}

DeviceKind selectDevice(const std::string& requested, const DeviceAvailability& available) {
    if (requested == "cpu") return DeviceKind::Cpu;
    if (requested == "auto")
        return available.cudaBackend && available.gpuCount > 0 ? DeviceKind::Cuda : DeviceKind::Cpu;
    if (requested == "cuda") {
        if (!available.cudaBackend)
            throw Error("--device cuda: this caustica was built without the CUDA backend "
                        "(rebuild with nvcc on PATH, or use --device cpu)");
        if (available.gpuCount <= 0)
            throw Error("--device cuda: no CUDA GPU found (cudaGetDeviceCount is 0; use --device "
                        "cpu or auto)");
        return DeviceKind::Cuda;
    }
    throw Error("--device " + requested + ": expected cpu, cuda or auto");
}

}  // namespace caustica
