// device_select_test.cpp — `--device cpu|cuda|auto` resolution, on any machine.
#include <gtest/gtest.h>

#include <string>

#include "caustica/parallel/backend.h"
#include "caustica/parallel/device_select.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

const DeviceAvailability kNoBackend{false, 0};
const DeviceAvailability kBackendNoGpu{true, 0};
const DeviceAvailability kGpu{true, 2};

TEST(DeviceSelect, CpuIsAlwaysCpu) {
    for (const auto& a : {kNoBackend, kBackendNoGpu, kGpu})
        EXPECT_EQ(selectDevice("cpu", a), DeviceKind::Cpu);
}

TEST(DeviceSelect, AutoPrefersTheGpuAndFallsBackToCpu) {
    EXPECT_EQ(selectDevice("auto", kNoBackend), DeviceKind::Cpu);
    EXPECT_EQ(selectDevice("auto", kBackendNoGpu), DeviceKind::Cpu);
    EXPECT_EQ(selectDevice("auto", kGpu), DeviceKind::Cuda);
}

std::string errorOf(const std::string& requested, const DeviceAvailability& a) {
    try {
        selectDevice(requested, a);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(DeviceSelect, CudaNeedsBackendAndGpu) {
    EXPECT_EQ(selectDevice("cuda", kGpu), DeviceKind::Cuda);
    const std::string noBackend = errorOf("cuda", kNoBackend);
    EXPECT_NE(noBackend.find("built without the CUDA backend"), std::string::npos) << noBackend;
    const std::string noGpu = errorOf("cuda", kBackendNoGpu);
    EXPECT_NE(noGpu.find("no CUDA GPU found"), std::string::npos) << noGpu;
    // One line each: the CLI prints them as "caustica: error: ...".
    EXPECT_EQ(noBackend.find('\n'), std::string::npos);
    EXPECT_EQ(noGpu.find('\n'), std::string::npos);
}

TEST(DeviceSelect, UnknownNameIsAnError) {
    EXPECT_THROW(selectDevice("tpu", kGpu), Error);
    EXPECT_THROW(selectDevice("", kNoBackend), Error);
}

TEST(DeviceSelect, AvailabilityFollowsTheInstalledBackend) {
    // This test program never registers a CUDA backend.
    if (gpuBackend() != nullptr) GTEST_SKIP() << "a GPU backend is installed";
    const DeviceAvailability a = currentDeviceAvailability();
    EXPECT_FALSE(a.cudaBackend);
    EXPECT_EQ(a.gpuCount, 0);
    EXPECT_EQ(selectDevice("auto", a), DeviceKind::Cpu);
}

}  // namespace
}  // namespace caustica
