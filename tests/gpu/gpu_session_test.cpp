// gpu_session_test.cpp — whole renders through the render session (render/renderer.h) on the GPU,
// for every integrator the session runs there: a render saved part way and resumed ends with the
// uninterrupted render's image bit for bit (the GPU's passes and iterations are deterministic:
// fixed-point photon sums, per-pixel sample streams), and a checkpoint written on the CPU resumes
// on the GPU (the render identity leaves the device out) and ends with the CPU's image up to
// rounding. MLT's checkpoints are tests/gpu/gpu_mlt_test.cpp's. Skips without a GPU.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "caustica/film/image_compare.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/renderer.h"
#include "common/gpu_test_setup.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

struct SessionCase {
    const char* name;         // test name suffix
    const char* integrator;
    const char* scene;
    const char* gpuMode;      // path only
    int samples;              // spp or iterations
    double relMseBound;       // CPU checkpoint resumed on the GPU vs the CPU's whole render
};

// Photon mapping gets the looser bound: FMA rounding sends a few photon paths through the water
// elsewhere on each device (scripts/gpu-parity measured 5e-5 whole, 7e-7 without the worst 1%).
const SessionCase kCases[] = {
    {"PathMegakernel", "path", "cornell-water", "megakernel", 6, 1e-3},
    {"PathWavefront", "path", "cornell-water", "wavefront", 6, 1e-3},
    {"Direct", "direct", "cornell-box", "megakernel", 6, 1e-3},
    {"Whitted", "whitted", "cornell-water", "megakernel", 6, 1e-3},
    {"Sppm", "sppm", "cornell-water", "megakernel", 5, 1e-2},
    {"Ppm", "ppm", "cornell-water", "megakernel", 5, 1e-2},
};

caustica::RenderRequest requestFor(const SessionCase& c, const char* device) {
    caustica::RenderRequest r;
    r.integrator = c.integrator;
    r.samplesPerPixel = c.samples;
    r.samplesPerPass = 2;  // several passes, so that the checkpoint falls between two
    r.seed = 11;
    r.device = device;
    r.gpuMode = c.gpuMode;
    r.accel = AccelKind::Bvh;  // the CPU traces the structure the GPU traces
    if (std::string(c.integrator) == "sppm" || std::string(c.integrator) == "ppm")
        r.integratorParams = {{"photon_count", IntegratorParam::Kind::Text, "8192", "--sppm-photons"}};
    return r;
}

Scene sceneFor(const SessionCase& c) {
    return loadScene(sourcePath(std::string("scenes/") + c.scene + "/scene.xml"), {{"width", "24"}, {"height", "18"}});
}

Image finish(Renderer& r) {
    while (!r.finished()) r.step();
    return r.develop();
}

class GpuSession : public ::testing::TestWithParam<SessionCase> {
protected:
    void SetUp() override {
        test::skipWithoutGpu("render sessions on the GPU");
        dir_ = fs::temp_directory_path() / ("caustica_gpu_session_" + std::string(GetParam().name));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string checkpoint() const { return (dir_ / "r.ckpt").string(); }

private:
    fs::path dir_;
};

TEST_P(GpuSession, AResumedRenderEndsWithTheUninterruptedImage) {
    const SessionCase& c = GetParam();
    const Scene scene = sceneFor(c);
    const caustica::RenderRequest r = requestFor(c, "cuda");
    Renderer whole(scene, r);
    ASSERT_EQ(whole.device().kind, DeviceKind::Cuda);
    const Image expected = finish(whole);
    Renderer first(scene, r);
    first.step();
    first.save(checkpoint());
    Renderer resumed(scene, r);
    resumed.load(checkpoint());
    EXPECT_GT(resumed.progress().samplesPerPixel, 0);
    EXPECT_LT(resumed.progress().samplesPerPixel, c.samples);
    const Image image = finish(resumed);
    ASSERT_EQ(image.rgb.size(), expected.rgb.size());
    EXPECT_TRUE(image.rgb == expected.rgb) << c.integrator << ": the resumed image differs";
    double sum = 0;
    for (float v : image.rgb) sum += v;
    EXPECT_GT(sum, 0);
}

TEST_P(GpuSession, ACpuCheckpointResumesOnTheGpu) {
    const SessionCase& c = GetParam();
    const Scene scene = sceneFor(c);
    const caustica::RenderRequest onCpu = requestFor(c, "cpu");
    Renderer cpuWhole(scene, onCpu);
    const Image cpuImage = finish(cpuWhole);
    Renderer cpuFirst(scene, onCpu);
    cpuFirst.step();
    cpuFirst.save(checkpoint());
    Renderer gpu(scene, requestFor(c, "cuda"));
    gpu.load(checkpoint());
    const Image image = finish(gpu);
    const ErrorMetrics m = compareImages(image, cpuImage);
    EXPECT_LT(m.relMse * (1 - m.relMseWorstShare), c.relMseBound)
        << c.integrator << ": relMSE " << m.relMse << ", worst 1% share " << m.relMseWorstShare;
}

INSTANTIATE_TEST_SUITE_P(Integrators, GpuSession, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<SessionCase>& info) { return info.param.name; });

}  // namespace
}  // namespace caustica::test
