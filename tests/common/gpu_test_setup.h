// gpu_test_setup.h — what every GPU test fixture's SetUp does first: register the CUDA backend,
// then skip on a machine without a usable GPU, or fail there when CAUSTICA_REQUIRE_GPU is set
// (scripts/gpu-check sets it): on a GPU machine, a runtime that cannot start must not read as a
// run of skipped, passing tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "cuda/cuda_backend.h"

namespace caustica::test {

inline bool gpuRequired() {
    const char* v = std::getenv("CAUSTICA_REQUIRE_GPU");
    return v != nullptr && *v != '\0' && std::string(v) != "0";
}

/// Call from a fixture's SetUp(): returns with nothing recorded when a GPU is usable; else records
/// a skip (or, with CAUSTICA_REQUIRE_GPU, a fatal failure), either of which stops the test body.
inline void skipWithoutGpu(const char* what) {
    registerCudaBackend();
    if (cudaDeviceCountOrZero() > 0) return;
    if (gpuRequired())
        GTEST_FAIL() << "CAUSTICA_REQUIRE_GPU is set, but the CUDA runtime finds no usable GPU: " << what
                     << " not exercised";
    GTEST_SKIP() << "no CUDA GPU on this machine (cudaGetDeviceCount is 0): " << what << " not exercised";
}

}  // namespace caustica::test
