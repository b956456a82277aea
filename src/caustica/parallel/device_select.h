// device_select.h — which device `caustica render --device cpu|cuda|auto` renders on.
#pragma once

#include <string>

#include "caustica/parallel/device.h"

namespace caustica {

/// What the program can offer: whether it was built with (and registered) the CUDA backend, and
/// how many GPUs that backend sees.
struct DeviceAvailability {
    bool cudaBackend = false;
    int gpuCount = 0;
};

/// The availability through the installed GPU backend (parallel/backend.h): no backend means a
/// binary without CUDA. Never throws.
DeviceAvailability currentDeviceAvailability();

/// "cpu" -> CPU; "cuda" -> CUDA, or caustica::Error (one line: built without CUDA, or no CUDA
/// GPU found); "auto" -> CUDA when the backend exists and sees a GPU, else CPU. Any other name
/// throws caustica::Error.
DeviceKind selectDevice(const std::string& requested, const DeviceAvailability& available);

}  // namespace caustica
