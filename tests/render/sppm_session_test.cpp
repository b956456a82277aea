// SPPM through the render session (render/sppm_session.cpp): it converges to the image the path
// tracer converges to (the Mitsuba 3 reference of cornell-box that the path tracer is tested
// against), its image is bit-identical on 1 and 2 threads, and a resumed render ends with the
// uninterrupted image.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "caustica/io/image_io.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/renderer.h"
#include "common/block_agreement.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

caustica::RenderRequest sppmRequest(int iterations, uint64_t seed, const char* photons, const char* radius) {
    caustica::RenderRequest r;
    r.integrator = "sppm";
    r.samplesPerPixel = iterations;
    r.seed = seed;
    r.device = "cpu";
    r.accel = AccelKind::Bvh;  // the own BVH: the same bits on every CPU (Embree's last bits differ)
    r.integratorParams = {{"photon_count", IntegratorParam::Kind::Text, photons, "--sppm-photons"},
                          {"initial_radius", IntegratorParam::Kind::Text, radius, "--sppm-radius"}};
    return r;
}

Image render(const Scene& scene, const caustica::RenderRequest& request, int threads = 0) {
    auto run = [&] {
        Renderer renderer(scene, request);
        while (!renderer.finished()) renderer.step();
        return renderer.develop();
    };
    if (threads > 0) return tbb::task_arena(threads).execute(run);
    return run();
}

// cornell-box at 32x32 against the 64x64 Mitsuba reference halved (its per-pixel variance
// halved too). Statistics as the MLT tests (common/block_agreement.h): 8x8-pixel block means per
// channel, our variance from R = 6 independent runs (seeds), a bound on the mean z^2 and the
// z-score of the image mean; and the same statistics must reject the runs made 5% brighter, so
// the test can fail. SPPM is consistent but biased at a finite radius (the density estimate
// blurs the flux over the disc, and photons near corners are missed or leak): the initial radius
// 0.03 is half a pixel's footprint at the back wall (the box spans [-1, 1]^3 over 32 pixels),
// and α = 2/3 shrinks it further, so the blur stays inside a pixel and the bias is below the
// 6 runs' noise (measured: see docs/SPPM.md).
TEST(SppmConvergence, CornellBoxAgreesWithTheReference) {
    const Scene scene =
        loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "32"}, {"height", "32"}});
    const std::string ref = sourcePath("scenes/cornell-box/reference/cornell-box-64");
    const Image refMean = halveImage(readImage(ref + ".exr"), false);
    const Image refVar = halveImage(readImage(ref + ".var.exr"), true);
    constexpr int kRuns = 6;
    std::vector<Image> runs;
    for (int r = 0; r < kRuns; ++r) runs.push_back(render(scene, sppmRequest(48, 100 + uint64_t(r), "16384", "0.03")));
    const BlockStats ours = blocksOfRuns(runs), reference = blocksOfReference(refMean, refVar);
    const Agreement a = compare(ours, reference);
    std::printf("sppm cornell-box 32x32: mean z^2 %.3f, image z %.3f, relative bias %.4f\n", a.meanZ2, a.imageZ,
                a.relBias);
    EXPECT_TRUE(a.passed(kRuns)) << "mean z^2 " << a.meanZ2 << ", image z " << a.imageZ;
    const Agreement brighter = compare(ours, reference, 1.05);
    EXPECT_FALSE(brighter.passed(kRuns)) << "a 5% brighter image passes: the test cannot tell";
}

TEST(SppmDeterminism, OneAndTwoThreadsGiveTheSameImage) {
    const Scene scene =
        loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "24"}, {"height", "24"}});
    const caustica::RenderRequest r = sppmRequest(3, 5, "4096", "0");
    const Image one = render(scene, r, 1), two = render(scene, r, 2);
    ASSERT_EQ(one.rgb.size(), two.rgb.size());
    EXPECT_TRUE(one.rgb == two.rgb) << "the images differ";
    double sum = 0;
    for (float v : one.rgb) sum += v;
    EXPECT_GT(sum, 0);
}

TEST(SppmResume, ResumedRenderEndsWithTheUninterruptedImage) {
    const fs::path dir = fs::temp_directory_path() / "caustica_sppm_resume";
    fs::create_directories(dir);
    const std::string ckpt = (dir / "r.ckpt").string();
    const Scene scene =
        loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "16"}, {"height", "16"}});
    const caustica::RenderRequest r = sppmRequest(5, 9, "2048", "0");
    Renderer whole(scene, r);
    while (!whole.finished()) whole.step();
    Renderer first(scene, r);
    for (int i = 0; i < 2; ++i) first.step();
    first.save(ckpt);
    Renderer resumed(scene, r);
    resumed.load(ckpt);
    EXPECT_EQ(resumed.progress().samplesPerPixel, 2);
    while (!resumed.finished()) resumed.step();
    EXPECT_TRUE(resumed.develop().rgb == whole.develop().rgb) << "the images differ";
    // Another photon count is another render: refused.
    caustica::RenderRequest other = sppmRequest(5, 9, "1024", "0");
    Renderer different(scene, other);
    EXPECT_THROW(different.load(ckpt), Error);
    // So is another photon roulette (another image: the same expectation, other paths).
    caustica::RenderRequest otherRoulette = r;
    otherRoulette.integratorParams.push_back({"photon_roulette", IntegratorParam::Kind::Text, "throughput",
                                              "--sppm-roulette"});
    Renderer differentRoulette(scene, otherRoulette);
    EXPECT_THROW(differentRoulette.load(ckpt), Error);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace caustica::test
