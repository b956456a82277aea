// gpu_mlt_test.cpp — Metropolis light transport on the GPU (the one MLT driver, mlt_driver.h,
// instantiated for the GPU): GPU MLT renders of
// cornell-box (64x64) against the Mitsuba 3 reference the CPU driver is tested against
// (tests/e2e/mlt_test.cpp; the checks of tests/common/mlt_reference_check.h), atomic against sort
// splats, the statistics the driver fills, checkpoints (resumed = uninterrupted; a CPU
// checkpoint resumes on the GPU), and its errors. Built only with the CUDA backend (target
// caustica_gpu_tests); every test that needs a GPU skips when cudaGetDeviceCount finds none.
#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/mlt/mlt_driver.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/io/scene_loader.h"
#include "caustica/util/error.h"
#include "common/gpu_test_setup.h"
#include "common/mlt_reference_check.h"
#include "cuda/cuda_backend.h"

namespace caustica {
namespace {

using test::checkMltAgainstReference;
using test::maxRelativeDifference;
using test::MltCase;
using test::smallMltSettings;
using test::splatComparisonScene;
using test::splatComparisonSettings;
using test::sourcePath;

PathSettings pathSettingsOf(const Scene& scene) {
    IntegratorParams params(scene.integrator);
    return readPathSettings(params);
}

/// The GPU's instantiation of the MLT driver.
std::unique_ptr<MltRenderer> makeGpuMltRenderer(const Scene& scene, const Accel& accel, const PathSettings& path,
                                                const MltSettings& settings, uint64_t seed) {
    return std::make_unique<MltRenderer>(makeMltDriver<GpuExec>(scene, accel, path, settings, seed));
}

class GpuMlt : public ::testing::Test {
protected:
    void SetUp() override {
        test::skipWithoutGpu("GPU MLT");
    }
};

Image renderGpuMlt(const Scene& scene, const Accel& accel, const MltSettings& settings, uint64_t seed,
                   double mutationsPerPixel, MltStats* stats = nullptr) {
    const std::unique_ptr<MltRenderer> mlt = makeGpuMltRenderer(scene, accel, pathSettingsOf(scene), settings, seed);
    mlt->bootstrap();
    do mlt->iterate();
    while (mlt->mutationsPerPixel() < mutationsPerPixel);
    if (stats) *stats = mlt->stats();
    return mlt->develop();
}

/// R GPU MLT runs of cornell-box (64x64, 96 mutations per pixel) against the Mitsuba reference;
/// with `checkPower`, an 8% brighter image must be rejected by the same statistics.
void checkAgainstReference(const MltSettings& settings, bool checkPower, int runs = 6) {
    const MltCase box{"scenes/cornell-box/scene.xml", "scenes/cornell-box/reference/cornell-box-64",
                      96, 0.08};
    checkMltAgainstReference(box, settings, AccelKind::Bvh, "gpu mlt", checkPower, runs,
                             [](const Scene& scene, const Accel& accel, const MltSettings& s,
                                uint64_t seed, double mpp) {
                                 return renderGpuMlt(scene, accel, s, seed, mpp);
                             });
}

TEST_F(GpuMlt, CornellBoxMatchesReference) { checkAgainstReference(smallMltSettings(), true); }

// Sort splats, two proposals (split transitions) and Morton sorting (the permutation kernels).
TEST_F(GpuMlt, CornellBoxSortSplatsTwoProposalsMortonSortedMatchesReference) {
    MltSettings s = smallMltSettings();
    s.splat = MltSplatKind::Sort;
    s.proposals = 2;
    s.sortEvery = 4;
    checkAgainstReference(s, false);
}

// The chains evolve identically whatever the splat method (same streams, no atomics outside the
// splats), so atomic and sort splats give the same image up to the order of float additions; sort
// splats are bit-identical from run to run.
TEST_F(GpuMlt, AtomicAndSortSplatsAgree) {
    const Scene scene = splatComparisonScene();
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = splatComparisonSettings();
    const Image sorted = renderGpuMlt(scene, accel, s, 3, 16), again = renderGpuMlt(scene, accel, s, 3, 16);
    EXPECT_EQ(sorted.rgb, again.rgb);
    s.splat = MltSplatKind::Atomic;
    const Image atomic = renderGpuMlt(scene, accel, s, 3, 16);
    EXPECT_LT(maxRelativeDifference(atomic, sorted), 1e-4);
}

TEST_F(GpuMlt, StatisticsAreFilled) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "16"}, {"height", "16"}});
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = smallMltSettings();
    s.chains = 256;
    s.bootstrapSamples = 4096;
    MltStats st;
    renderGpuMlt(scene, accel, s, 5, 8, &st);
    const PathSettings path = pathSettingsOf(scene);
    EXPECT_EQ(st.bytesPerChain, mltBytesPerChain(MltStateKind::Compact, mltStoredBounces(path)));
    EXPECT_EQ(st.stateBytes, st.bytesPerChain * s.chains);
    EXPECT_EQ(st.bootstrapSamples, 4096u);
    EXPECT_EQ(st.iterations, 8u);  // 16 x 16 x 8 mutations / 256 chains
    EXPECT_EQ(st.proposals, 8u * s.chains);
    EXPECT_GT(st.accepted, 0u);
    EXPECT_LT(st.accepted, st.proposals);
    EXPECT_GT(st.rays, st.proposals);  // bootstrap and chain starts included
    EXPECT_GT(st.b, 0);
    EXPECT_GT(st.traceSeconds, 0);
}

// The CPU checkpoint tests' scene (tests/e2e/mlt_test.cpp), with Morton sorting so that the
// resumed chains' permutation and the store's transposition are exercised.
MltSettings checkpointSettings() {
    MltSettings s = smallMltSettings();
    s.chains = 256;
    s.bootstrapSamples = 4096;
    s.splat = MltSplatKind::Sort;  // bit-identical from run to run
    s.sortEvery = 2;
    return s;
}

/// A GPU renderer bootstrapped and stepped `iterations` times (developing after each step with
/// `developEachStep`, which must change nothing).
std::unique_ptr<MltRenderer> gpuRendered(const Scene& scene, const Accel& accel, const MltSettings& s, int iterations,
                                         bool developEachStep = false) {
    std::unique_ptr<MltRenderer> mlt = makeGpuMltRenderer(scene, accel, pathSettingsOf(scene), s, 5);
    mlt->bootstrap();
    for (int i = 0; i < iterations; ++i) {
        mlt->iterate();
        if (developEachStep) mlt->develop();
    }
    return mlt;
}

// A GPU render saved after some iterations and resumed in a new renderer ends with the image an
// uninterrupted one gives, bit for bit, with the same counters.
TEST_F(GpuMlt, ASavedAndResumedRenderEqualsAnUninterruptedOne) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "16"}, {"height", "12"}});
    const Accel accel(scene, AccelKind::Bvh);
    const MltSettings s = checkpointSettings();
    const PathSettings path = pathSettingsOf(scene);
    const std::unique_ptr<MltRenderer> whole = gpuRendered(scene, accel, s, 8);
    std::stringstream file;
    gpuRendered(scene, accel, s, 3)->save(file);
    const std::unique_ptr<MltRenderer> resumed = makeGpuMltRenderer(scene, accel, path, s, 5);
    EXPECT_FALSE(resumed->started());
    resumed->load(file);
    EXPECT_TRUE(resumed->started());
    for (int i = 0; i < 5; ++i) resumed->iterate();
    EXPECT_EQ(resumed->develop().rgb, whole->develop().rgb);
    EXPECT_EQ(resumed->stats().iterations, whole->stats().iterations);
    EXPECT_EQ(resumed->stats().accepted, whole->stats().accepted);
    EXPECT_EQ(resumed->stats().rays, whole->stats().rays);
    EXPECT_EQ(resumed->stats().b, whole->stats().b);
}

// Splats in batches of 3 iterations: a checkpoint after 4 iterations carries the unfinished batch,
// developing in the middle of a batch changes nothing, and a CPU checkpoint with a pending batch
// develops on the GPU to the CPU's image up to rounding (the GPU contracts multiply-adds).
TEST_F(GpuMlt, UnfinishedSplatBatchesAreResumedAndDeveloped) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "16"}, {"height", "12"}});
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = checkpointSettings();
    s.splatBatch = 3;
    const PathSettings path = pathSettingsOf(scene);
    const std::unique_ptr<MltRenderer> whole = gpuRendered(scene, accel, s, 7);
    std::stringstream file;
    gpuRendered(scene, accel, s, 4, true)->save(file);
    const std::unique_ptr<MltRenderer> resumed = makeGpuMltRenderer(scene, accel, path, s, 5);
    resumed->load(file);
    for (int i = 0; i < 3; ++i) resumed->iterate();
    EXPECT_EQ(resumed->develop().rgb, whole->develop().rgb);

    MltRenderer cpu(scene, accel, path, s, 5);
    cpu.bootstrap();
    for (int i = 0; i < 4; ++i) cpu.iterate();
    std::stringstream cpuFile;
    cpu.save(cpuFile);
    const std::unique_ptr<MltRenderer> gpu = makeGpuMltRenderer(scene, accel, path, s, 5);
    std::stringstream in(cpuFile.str());
    gpu->load(in);
    EXPECT_LT(maxRelativeDifference(gpu->develop(), cpu.develop()), 1e-5);
}

// Both drivers write the same format (chain-major store): a CPU checkpoint loads into the GPU
// driver, which develops the same image from it and writes it back byte for byte; then it goes on.
TEST_F(GpuMlt, ACpuCheckpointResumesOnTheGpu) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "16"}, {"height", "12"}});
    const Accel accel(scene, AccelKind::Bvh);
    const MltSettings s = checkpointSettings();
    const PathSettings path = pathSettingsOf(scene);
    MltRenderer cpu(scene, accel, path, s, 5);
    cpu.bootstrap();
    for (int i = 0; i < 3; ++i) cpu.iterate();
    std::stringstream cpuFile;
    cpu.save(cpuFile);

    const std::unique_ptr<MltRenderer> gpu = makeGpuMltRenderer(scene, accel, path, s, 5);
    std::stringstream in(cpuFile.str());
    gpu->load(in);
    EXPECT_EQ(gpu->develop().rgb, cpu.develop().rgb);
    std::stringstream gpuFile;
    gpu->save(gpuFile);
    EXPECT_TRUE(gpuFile.str() == cpuFile.str()) << "the GPU rewrote a CPU checkpoint differently";
    for (int i = 0; i < 3; ++i) gpu->iterate();
    EXPECT_EQ(gpu->stats().iterations, 6u);
    EXPECT_GT(gpu->stats().accepted, cpu.stats().accepted);
}

// The memory estimate (mlt_gpu_memory.h) refuses, before allocating, a bootstrap of 2^36 samples
// (768 GiB of bootstrap arrays) with one line that names what to lower.
TEST_F(GpuMlt, ARenderThatDoesNotFitIsRefusedWithOneLine) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "8"}, {"height", "8"}});
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = smallMltSettings();
    s.bootstrapSamples = uint64_t(1) << 36;
    try {
        makeGpuMltRenderer(scene, accel, pathSettingsOf(scene), s, 1);
        FAIL() << "no exception";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("GPU memory: MLT needs about"), std::string::npos) << what;
        EXPECT_NE(what.find("--mlt-bootstrap"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(GpuMltSettings, FloatStateIsRefusedBeforeTouchingTheGpu) {
    registerCudaBackend();
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "8"}, {"height", "8"}});
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = smallMltSettings();
    s.state = MltStateKind::Float;
    try {
        makeGpuMltRenderer(scene, accel, pathSettingsOf(scene), s, 1);
        FAIL() << "no exception";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("--mlt-state float"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

TEST(GpuMltWithoutGpu, ConstructionFailsWithAnError) {
    registerCudaBackend();
    if (cudaDeviceCountOrZero() > 0) GTEST_SKIP() << "a GPU is present";
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "8"}, {"height", "8"}});
    const Accel accel(scene, AccelKind::Bvh);
    EXPECT_THROW(makeGpuMltRenderer(scene, accel, pathSettingsOf(scene), smallMltSettings(), 1),
                 Error);
}

}  // namespace
}  // namespace caustica
