// cuda_check.h — every CUDA runtime call is checked: failures become caustica::Error.
#pragma once

#include <string>

#include <cuda_runtime_api.h>

#include "caustica/util/error.h"

namespace caustica {

/// Throws caustica::Error("file:line: <call> failed: <cudaErrorName>: <cudaGetErrorString>")
/// when `status` is not cudaSuccess. Host code only.
inline void checkCuda(cudaError_t status, const char* call, const char* file, int line) {
    if (status == cudaSuccess) return;
    throw Error(file, line,
                std::string(call) + " failed: " + cudaGetErrorName(status) + ": " +
                    cudaGetErrorString(status));
}

}  // namespace caustica

/// Checks one CUDA runtime call: CA_CUDA_CHECK(cudaMalloc(&p, bytes));
#define CA_CUDA_CHECK(call) ::caustica::checkCuda((call), #call, __FILE__, __LINE__)
