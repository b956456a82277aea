// The photon mappers' choices through the render session: both directions (deposit, gather),
// every lookup structure and the coherence orders give the same image to the bit (the sums are
// fixed point); ppm, the global radius schedule and the throughput photon roulette converge to
// the reference the path tracer is tested against (block t-test, common/block_agreement.h); sppm
// converges on cornell-water (the caustics under the water) and glass-caustic (a focused
// caustic); ppm resumes to the uninterrupted image; max_passes ends a render.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

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

using Params = std::vector<std::pair<std::string, std::string>>;

caustica::RenderRequest request(const char* integrator, int passes, uint64_t seed, const Params& params) {
    caustica::RenderRequest r;
    r.integrator = integrator;
    r.samplesPerPixel = passes;
    r.seed = seed;
    r.device = "cpu";
    r.accel = AccelKind::Bvh;  // the own BVH: the same bits on every CPU
    for (const auto& [name, value] : params)
        r.integratorParams.push_back({name, IntegratorParam::Kind::Text, value, "--" + name});
    return r;
}

Image render(const Scene& scene, const caustica::RenderRequest& r) {
    Renderer renderer(scene, r);
    while (!renderer.finished()) renderer.step();
    return renderer.develop();
}

/// R runs (seeds) at 32x32 against the scene's 64x64 Mitsuba reference halved; the same
/// statistics must reject the runs made 5% brighter, so that the test can fail.
void expectAgreement(const char* sceneName, const char* integrator, int passes, const Params& params) {
    const Scene scene = loadScene(sourcePath(std::string("scenes/") + sceneName + "/scene.xml"),
                                  {{"width", "32"}, {"height", "32"}});
    const std::string ref = sourcePath(std::string("scenes/") + sceneName + "/reference/" + sceneName + "-64");
    const Image refMean = halveImage(readImage(ref + ".exr"), false);
    const Image refVar = halveImage(readImage(ref + ".var.exr"), true);
    constexpr int kRuns = 6;
    std::vector<Image> runs;
    for (int r = 0; r < kRuns; ++r) runs.push_back(render(scene, request(integrator, passes, 200 + uint64_t(r), params)));
    const BlockStats ours = blocksOfRuns(runs), reference = blocksOfReference(refMean, refVar);
    const Agreement a = compare(ours, reference);
    std::printf("%s %s 32x32: mean z^2 %.3f, image z %.3f, relative bias %.4f\n", integrator, sceneName, a.meanZ2,
                a.imageZ, a.relBias);
    EXPECT_TRUE(a.passed(kRuns)) << "mean z^2 " << a.meanZ2 << ", image z " << a.imageZ;
    EXPECT_FALSE(compare(ours, reference, 1.05).passed(kRuns)) << "a 5% brighter image passes: the test cannot tell";
}

TEST(PhotonMapper, DirectionsStructuresAndOrdersGiveTheSameImage) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "24"}, {"height", "24"}});
    const Params base = {{"photon_count", "4096"}};
    const std::vector<Params> variants = {
        {{"direction", "gather"}, {"structure", "hash"}},
        {{"direction", "gather"}, {"structure", "grid"}, {"sort_photons", "false"}},
        {{"direction", "gather"}, {"structure", "brute"}, {"hitpoint_order", "none"}},
        {{"direction", "deposit"}, {"structure", "grid"}, {"hitpoint_order", "kmeans"}},
        {{"direction", "gather"}, {"structure", "hash"}, {"hitpoint_order", "kmeans"}},
        {{"direction", "deposit"}, {"structure", "brute"}},
        {{"direction", "gather"}, {"structure", "kdtree"}},
        {{"direction", "deposit"}, {"structure", "kdtree"}},
        {{"direction", "gather"}, {"structure", "multihash"}},
        {{"direction", "deposit"}, {"structure", "multihash"}, {"hitpoint_order", "none"}},
    };
    for (const char* integrator : {"sppm", "ppm"}) {
        SCOPED_TRACE(integrator);
        const Image reference = render(scene, request(integrator, 2, 3, base));
        double sum = 0;
        for (float v : reference.rgb) sum += v;
        EXPECT_GT(sum, 0);
        for (const Params& v : variants) {
            Params p = base;
            p.insert(p.end(), v.begin(), v.end());
            EXPECT_TRUE(render(scene, request(integrator, 2, 3, p)).rgb == reference.rgb)
                << v[0].second << " / " << v[1].second;
        }
    }
}

/// The session's summary (printSummary) as text.
std::string summaryOf(const Renderer& renderer) {
    std::FILE* f = std::tmpfile();
    renderer.session().printSummary(f);
    std::rewind(f);
    std::string text;
    for (int c; (c = std::fgetc(f)) != EOF;) text += char(c);
    std::fclose(f);
    return text;
}

// Direction "auto" (the default): with few photons stored per visible point (32 photon paths
// for 576 pixels) it times two passes in each direction and keeps the faster; with many (4096)
// it gathers without timing. Either way the image is the same bits as both fixed directions'.
TEST(PhotonMapper, AutoDirectionChoosesAndKeepsTheImage) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "24"}, {"height", "24"}});
    for (const char* photons : {"32", "4096"}) {
        SCOPED_TRACE(photons);
        const bool timed = std::string(photons) == "32";
        Renderer renderer(scene, request("sppm", 6, 3, {{"photon_count", photons}}));
        while (!renderer.finished()) renderer.step();
        const Image image = renderer.develop();
        EXPECT_TRUE(image.rgb == render(scene, request("sppm", 6, 3, {{"photon_count", photons}, {"direction", "gather"}})).rgb);
        EXPECT_TRUE(image.rgb == render(scene, request("sppm", 6, 3, {{"photon_count", photons}, {"direction", "deposit"}})).rgb);
        std::string chosen;
        for (const auto& [key, value] : renderer.session().statsJson())
            if (key == "sppm_direction") chosen = value;
        const std::string summary = summaryOf(renderer);
        if (timed) {
            EXPECT_TRUE(chosen == "\"gather\"" || chosen == "\"deposit\"") << chosen;
            EXPECT_NE(summary.find("passes timed: gather"), std::string::npos) << summary;
        } else {
            EXPECT_EQ(chosen, "\"gather\"");
            EXPECT_NE(summary.find("direction gather (auto:"), std::string::npos) << summary;
            EXPECT_EQ(summary.find("passes timed"), std::string::npos) << summary;
        }
    }
}

TEST(PhotonMapper, GatherIsTheSameOnOneAndTwoThreads) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "24"}, {"height", "24"}});
    const caustica::RenderRequest r = request("sppm", 2, 5, {{"photon_count", "4096"}, {"direction", "gather"}});
    const Image one = tbb::task_arena(1).execute([&] { return render(scene, r); });
    const Image two = tbb::task_arena(2).execute([&] { return render(scene, r); });
    EXPECT_TRUE(one.rgb == two.rgb);
}

TEST(PhotonMapperConvergence, PpmCornellBoxAgreesWithTheReference) {
    expectAgreement("cornell-box", "ppm", 48, {{"photon_count", "16384"}, {"initial_radius", "0.03"}, {"hitpoints", "4"}});
}

TEST(PhotonMapperConvergence, GlobalScheduleCornellBoxAgreesWithTheReference) {
    expectAgreement("cornell-box", "sppm", 48,
                    {{"photon_count", "16384"}, {"initial_radius", "0.03"}, {"radius_schedule", "global"}});
}

// Photon paths with the path tracer's roulette (from rr_depth on) instead of the default albedo rule.
TEST(PhotonMapperConvergence, ThroughputRouletteCornellBoxAgreesWithTheReference) {
    expectAgreement("cornell-box", "sppm", 48,
                    {{"photon_count", "16384"}, {"initial_radius", "0.03"}, {"photon_roulette", "throughput"}});
}

// The headline scene: caustics on the floor and the walls under the water, seen through the
// water's front face; the light reaches them only through the wavy surface, by photons.
TEST(PhotonMapperConvergence, SppmCornellWaterAgreesWithTheReference) {
    expectAgreement("cornell-water", "sppm", 48, {{"photon_count", "16384"}, {"initial_radius", "0.03"}});
}

// A glass ball focusing a small light into a sub-pixel caustic inside its shadow; a second, large
// light selected half the time (uniform light selection). Many iterations of few photons: the
// key light's reflection on the ball is a sub-pixel highlight that about one camera sample in 60
// finds, so at ~100 iterations (camera samples per pixel) its block is heavy-tailed, most runs
// miss it, and the t statistic means nothing there.
TEST(PhotonMapperConvergence, SppmGlassCausticAgreesWithTheReference) {
    expectAgreement("glass-caustic", "sppm", 384, {{"photon_count", "4096"}, {"initial_radius", "0.01"}});
}

TEST(PhotonMapper, PpmResumesToTheUninterruptedImage) {
    const fs::path dir = fs::temp_directory_path() / "caustica_ppm_resume";
    fs::create_directories(dir);
    const std::string ckpt = (dir / "r.ckpt").string();
    const Scene scene = loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "16"}, {"height", "16"}});
    const caustica::RenderRequest r = request("ppm", 4, 9, {{"photon_count", "2048"}, {"hitpoints", "2"}});
    const Image whole = render(scene, r);
    Renderer first(scene, r);
    for (int i = 0; i < 2; ++i) first.step();
    first.save(ckpt);
    Renderer resumed(scene, r);
    resumed.load(ckpt);
    while (!resumed.finished()) resumed.step();
    EXPECT_TRUE(resumed.develop().rgb == whole.rgb) << "the images differ";
    // Other hitpoints per pixel: another render, refused.
    Renderer different(scene, request("ppm", 4, 9, {{"photon_count", "2048"}, {"hitpoints", "3"}}));
    EXPECT_THROW(different.load(ckpt), Error);
    fs::remove_all(dir);
}

TEST(PhotonMapper, MaxPassesEndsTheRenderWhenNoSampleCountIsGiven) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "8"}, {"height", "8"}});
    Renderer renderer(scene, request("sppm", 0, 1, {{"photon_count", "256"}, {"max_passes", "3"}}));
    int steps = 0;
    while (!renderer.finished() && steps < 100) {
        renderer.step();
        ++steps;
    }
    EXPECT_EQ(steps, 3);
    EXPECT_EQ(renderer.progress().samplesPerPixel, 3);
}

// The integrator's `seed` picks the streams when the command line gives no --seed; --seed wins.
TEST(PhotonMapper, IntegratorSeedUnlessTheCommandLineGivesOne) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-box/scene.xml"), {{"width", "8"}, {"height", "8"}});
    auto withSeed = [&](const char* seed, bool commandLine) {
        caustica::RenderRequest r = request("sppm", 2, 1, {{"photon_count", "256"}, {"seed", seed}});
        if (!commandLine) r.seed.reset();
        return render(scene, r).rgb;
    };
    EXPECT_TRUE(withSeed("7", false) != withSeed("8", false));
    EXPECT_TRUE(withSeed("7", false) == withSeed("7", false));
    EXPECT_TRUE(withSeed("7", true) == withSeed("8", true));
}

}  // namespace
}  // namespace caustica::test
