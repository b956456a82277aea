// gpu_mlt_test.cpp — Metropolis light transport on the GPU (cuda/gpu_mlt.h): GPU MLT renders of
// cornell-box (64x64) against the Mitsuba 3 reference the CPU driver is tested against
// (tests/e2e/mlt_test.cpp; the block statistics of tests/common/block_agreement.h), atomic against sort splats, the
// statistics the driver fills, and its errors. Built only with the CUDA backend (target
// caustica_gpu_tests); every test that needs a GPU skips when cudaGetDeviceCount finds none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_loop.h"
#include "caustica/integrators/path/path_integrator.h"
#include "caustica/io/image_io.h"
#include "caustica/io/scene_loader.h"
#include "caustica/util/error.h"
#include "common/block_agreement.h"
#include "cuda/cuda_backend.h"
#include "cuda/gpu_mlt.h"

namespace caustica {
namespace {

std::string sourcePath(const std::string& relative) {
    return std::string(CAUSTICA_SOURCE_DIR) + "/" + relative;
}

class GpuMlt : public ::testing::Test {
protected:
    void SetUp() override {
        registerCudaBackend();
        if (cudaDeviceCountOrZero() == 0)
            GTEST_SKIP() << "no CUDA GPU on this machine (cudaGetDeviceCount is 0): GPU MLT not exercised";
    }
};

MltSettings smallSettings() {
    MltSettings s;
    s.chains = 4096;
    s.bootstrapSamples = 1 << 17;
    return s;
}

Image renderGpuMlt(const Scene& scene, const Accel& accel, const MltSettings& settings, uint64_t seed,
                   double mutationsPerPixel, MltStats* stats = nullptr) {
    const std::unique_ptr<MltRenderer> mlt =
        makeGpuMltRenderer(scene, *accel.bvh(), pathSettingsFrom(scene.integrator), settings, seed);
    MltBudget budget;
    budget.mutationsPerPixel = mutationsPerPixel;
    runMlt(*mlt, budget);
    if (stats) *stats = mlt->stats();
    return mlt->develop();
}

using test::Agreement;
using test::BlockStats;
using test::blocksOfReference;
using test::blocksOfRuns;
using test::compare;

/// R GPU MLT runs of cornell-box (64x64, 96 mutations per pixel) against the Mitsuba reference;
/// with `checkPower`, an 8% brighter image must be rejected by the same statistics.
void checkAgainstReference(const MltSettings& settings, bool checkPower, int runs = 6) {
    const std::string ref = sourcePath("scenes/cornell-box/reference/cornell-box-64");
    const Image mean = readImage(ref + ".exr"), var = readImage(ref + ".var.exr");
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"),
                                  {{"width", std::to_string(mean.width)}, {"height", std::to_string(mean.height)}});
    const Accel accel(scene, AccelKind::Bvh);
    std::vector<Image> images;
    for (int r = 0; r < runs; ++r) images.push_back(renderGpuMlt(scene, accel, settings, 100 + uint64_t(r), 96));
    const BlockStats ours = blocksOfRuns(images), theirs = blocksOfReference(mean, var);
    const Agreement a = compare(ours, theirs);
    std::printf("gpu mlt (k=%u, %s, sort every %u): block mean z^2 %.2f, image-mean z %.2f, bias %+.2f%%\n",
                settings.proposals, settings.splat == MltSplatKind::Atomic ? "atomic" : "sort", settings.sortEvery,
                a.meanZ2, a.imageZ, 100 * a.relBias);
    EXPECT_TRUE(a.passed(runs)) << "block mean z^2 " << a.meanZ2 << ", image-mean z " << a.imageZ;
    if (!checkPower) return;
    const Agreement wrong = compare(ours, theirs, 1.08);
    EXPECT_FALSE(wrong.passed(runs)) << "an 8% error is not detected: mean z^2 " << wrong.meanZ2;
}

TEST_F(GpuMlt, CornellBoxMatchesReference) { checkAgainstReference(smallSettings(), true); }

// Sort splats, two proposals (split transitions) and Morton sorting (the permutation kernels).
TEST_F(GpuMlt, CornellBoxSortSplatsTwoProposalsMortonSortedMatchesReference) {
    MltSettings s = smallSettings();
    s.splat = MltSplatKind::Sort;
    s.proposals = 2;
    s.sortEvery = 4;
    checkAgainstReference(s, false);
}

// The chains evolve identically whatever the splat method (same streams, no atomics outside the
// splats), so atomic and sort splats give the same image up to the order of float additions; sort
// splats are bit-identical from run to run.
TEST_F(GpuMlt, AtomicAndSortSplatsAgree) {
    Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "24"}, {"height", "16"}});
    scene.film.filter = FilterDesc{FilterType::Gaussian, 2.0f, 0.5f};
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = smallSettings();
    s.chains = 512;
    s.bootstrapSamples = 4096;
    s.sortEvery = 3;
    s.splat = MltSplatKind::Sort;
    const Image sorted = renderGpuMlt(scene, accel, s, 3, 16), again = renderGpuMlt(scene, accel, s, 3, 16);
    EXPECT_EQ(sorted.rgb, again.rgb);
    s.splat = MltSplatKind::Atomic;
    const Image atomic = renderGpuMlt(scene, accel, s, 3, 16);
    double maxRel = 0;
    for (size_t i = 0; i < atomic.rgb.size(); ++i)
        maxRel = std::max(maxRel, std::fabs(double(atomic.rgb[i]) - sorted.rgb[i]) / (std::fabs(double(sorted.rgb[i])) + 1e-3));
    EXPECT_LT(maxRel, 1e-4);
}

TEST_F(GpuMlt, StatisticsAreFilled) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "16"}, {"height", "16"}});
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = smallSettings();
    s.chains = 256;
    s.bootstrapSamples = 4096;
    MltStats st;
    renderGpuMlt(scene, accel, s, 5, 8, &st);
    const PathSettings path = pathSettingsFrom(scene.integrator);
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

TEST(GpuMltSettings, FloatStateIsRefusedBeforeTouchingTheGpu) {
    registerCudaBackend();
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "8"}, {"height", "8"}});
    const Accel accel(scene, AccelKind::Bvh);
    MltSettings s = smallSettings();
    s.state = MltStateKind::Float;
    try {
        makeGpuMltRenderer(scene, *accel.bvh(), pathSettingsFrom(scene.integrator), s, 1);
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
    EXPECT_THROW(makeGpuMltRenderer(scene, *accel.bvh(), pathSettingsFrom(scene.integrator), smallSettings(), 1),
                 Error);
}

}  // namespace
}  // namespace caustica
