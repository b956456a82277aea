// aov_render_test.cpp — AOVs of a render (render/aov_session.h) for every integrator: values
// against known geometry (a plane seen by an orthographic camera), Mitsuba's aov integrator in a
// scene and --aov, the variance against a hand-computed sample variance (path, direct) and
// against the developed steps' spread (batch means: mlt, sppm, ppm), thread-count independence,
// checkpoints, the layered EXR output, and the refusals.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "caustica/film/film.h"
#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/render_outputs.h"
#include "caustica/render/renderer.h"
#include "io/scene_test_util.h"

namespace caustica::test {
namespace {

constexpr const char* kAllGeometric =
    "dd.y:depth,nn:sh_normal,ng:geo_normal,p:position,uv:uv,alb:albedo,pi:prim_index,si:shape_"
    "index";

/// An orthographic camera at z = 5 looking down at the rectangle [-2, 2]² in z = 0 (it sees
/// [-1, 1]²: film x -> world x, film y -> world -y), 16 x 16 pixels, box filter; a sphere light
/// outside the view. `shift` moves the rectangle out of the view.
std::string planeScene(const std::string& integrator, float shift = 0) {
    return R"(<scene version="3.0.0">
)" + integrator +
           R"(
    <sensor type="orthographic">
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
            <rfilter type="box"/></film>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="2"/><translate x=")" +
           std::to_string(shift) + R"("/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>
    </shape>
    <shape type="sphere"><float name="radius" value="0.3"/><point name="center" x="3" y="0" z="1"/>
        <emitter type="area"><rgb name="radiance" value="4"/></emitter></shape>
</scene>
)";
}

const std::string kPath =
    R"(<integrator type="path"><integer name="max_depth" value="3"/></integrator>)";

RenderRequest request(const std::string& aovs, const std::string& integrator = "") {
    RenderRequest r;
    r.device = "cpu";
    r.seed = 3;
    r.samplesPerPixel = 4;
    r.samplesPerPass = 2;
    r.aovs = aovs;
    r.integrator = integrator;
    if (integrator == "mlt")
        r.integratorParams = {
            {"chains", IntegratorParam::Kind::Text, "16", "--mlt-chains"},
            {"luminance_samples", IntegratorParam::Kind::Text, "256", "--mlt-bootstrap"},
            {"splat", IntegratorParam::Kind::Text, "sort", "--splat"}};
    if (integrator == "sppm")
        r.integratorParams = {
            {"photon_count", IntegratorParam::Kind::Text, "2048", "--sppm-photons"},
            {"initial_radius", IntegratorParam::Kind::Text, "0", "--sppm-radius"}};
    return r;
}

std::unique_ptr<Renderer> makeRenderer(const TempDir& dir, const std::string& xml,
                                       const RenderRequest& r) {
    std::vector<std::string> warnings;
    return std::make_unique<Renderer>(loadScene(dir.write("scene.xml", xml), {}, &warnings), r);
}

AovImage renderAovs(const TempDir& dir, const std::string& xml, const RenderRequest& r) {
    auto renderer = makeRenderer(dir, xml, r);
    while (!renderer->finished()) renderer->step();
    return renderer->developAovs();
}

TEST(AovRender, PlaneValuesMatchTheGeometry) {
    TempDir dir;
    const AovImage a = renderAovs(dir, planeScene(kPath), request(kAllGeometric));
    ASSERT_EQ(a.channels.size(), 17u);
    EXPECT_EQ(a.channels[0], "dd.y.T");
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            SCOPED_TRACE(testing::Message() << "pixel " << x << "," << y);
            // Depth: from the camera's near plane (Mitsuba's near_clip 0.01) to z = 0.
            EXPECT_NEAR(a.at(x, y, 0), 4.99f, 1e-5f);
            for (int c : {1, 4}) {  // sh_normal, geo_normal: +z
                EXPECT_EQ(a.at(x, y, size_t(c)), 0.0f);
                EXPECT_EQ(a.at(x, y, size_t(c + 1)), 0.0f);
                EXPECT_EQ(a.at(x, y, size_t(c + 2)), 1.0f);
            }
            // Position: the pixel's mean sample, within half a pixel (1/16) of its centre.
            const float px = a.at(x, y, 7), py = a.at(x, y, 8);
            EXPECT_NEAR(px, -1 + (x + 0.5f) / 8, 1.0f / 16);
            EXPECT_NEAR(py, 1 - (y + 0.5f) / 8, 1.0f / 16);
            EXPECT_EQ(a.at(x, y, 9), 0.0f);
            // uv of Mitsuba's rectangle: (local + 1) / 2, local = world / 2, linear: exact means.
            EXPECT_NEAR(a.at(x, y, 10), px / 4 + 0.5f, 1e-5f);
            EXPECT_NEAR(a.at(x, y, 11), py / 4 + 0.5f, 1e-5f);
            EXPECT_FLOAT_EQ(a.at(x, y, 12), 0.3f);  // albedo: the diffuse reflectance
            EXPECT_FLOAT_EQ(a.at(x, y, 13), 0.5f);
            EXPECT_FLOAT_EQ(a.at(x, y, 14), 0.7f);
            // prim_index: triangle 0 (x > y) or 1, away from the diagonal; shape_index: 1 + shape
            // 0.
            const float cx = -1 + (x + 0.5f) / 8, cy = 1 - (y + 0.5f) / 8;
            if (std::abs(cx - cy) > 0.3f) {
                EXPECT_EQ(a.at(x, y, 15), cx > cy ? 0.0f : 1.0f);
            }
            EXPECT_EQ(a.at(x, y, 16), 1.0f);
        }
}

TEST(AovRender, EveryChannelIsZeroWhereTheCameraRayMisses) {
    TempDir dir;
    const AovImage a = renderAovs(dir, planeScene(kPath, 20), request(kAllGeometric));
    for (float v : a.values) EXPECT_EQ(v, 0.0f);
}

// Depth is integrator-independent here (a plane of constant depth): every integrator fills it.
// path and direct trace the same camera samples, so all their AOVs agree bit for bit.
TEST(AovRender, EveryIntegratorFillsTheAovs) {
    TempDir dir;
    const AovImage path = renderAovs(dir, planeScene(kPath), request(kAllGeometric, "path"));
    for (const char* integrator : {"direct", "mlt", "sppm"}) {
        SCOPED_TRACE(integrator);
        const AovImage a = renderAovs(dir, planeScene(kPath), request(kAllGeometric, integrator));
        ASSERT_EQ(a.values.size(), path.values.size());
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                EXPECT_NEAR(a.at(x, y, 0), 4.99f, 1e-5f);
                EXPECT_EQ(a.at(x, y, 16), 1.0f);
            }
        if (std::string(integrator) == "direct") {
            EXPECT_TRUE(a.values == path.values);
        }
    }
}

// path (megakernel and wavefront), direct and whitted trace each camera ray once for the image and
// the AOVs: the image and the rays counted are those of a render without AOVs, and the AOVs the
// same bit for bit in every one of them.
TEST(AovRender, PixelPassesTraceTheCameraRayOnceForImageAndAovs) {
    TempDir dir;
    auto run = [&](const std::string& aovs, const std::string& integrator, const std::string& mode) {
        RenderRequest r = request(aovs, integrator);
        r.pathMode = mode;
        auto renderer = makeRenderer(dir, planeScene(kPath), r);
        while (!renderer->finished()) renderer->step();
        return renderer;
    };
    const auto wavefront = run(kAllGeometric, "path", "wavefront");
    for (const char* integrator : {"path", "direct", "whitted"}) {
        SCOPED_TRACE(integrator);
        const auto with = run(kAllGeometric, integrator, "megakernel");
        const auto without = run("", integrator, "megakernel");
        EXPECT_TRUE(with->develop().rgb == without->develop().rgb);
        EXPECT_EQ(with->stats().rays, without->stats().rays);
        EXPECT_TRUE(with->developAovs().values == wavefront->developAovs().values);
    }
    // The wavefront's AOVs take the hits of its first extend stage: no ray is added.
    const auto wavefrontWithout = run("", "path", "wavefront");
    EXPECT_TRUE(wavefront->develop().rgb == wavefrontWithout->develop().rgb);
    EXPECT_EQ(wavefront->stats().rays, wavefrontWithout->stats().rays);
}

// With max_depth 0 no path traces a segment, yet the AOVs are those of the camera rays' hits:
// the wavefront traces them for the AOVs alone, as the megakernel does.
TEST(AovRender, WavefrontAovsWithoutAnySegmentMatchTheMegakernel) {
    TempDir dir;
    const std::string depth0 = R"(<integrator type="path"><integer name="max_depth" value="0"/></integrator>)";
    auto run = [&](const std::string& mode) {
        RenderRequest r = request(kAllGeometric, "path");
        r.pathMode = mode;
        auto renderer = makeRenderer(dir, planeScene(depth0), r);
        while (!renderer->finished()) renderer->step();
        return renderer->developAovs();
    };
    const auto megakernel = run("megakernel"), wavefront = run("wavefront");
    EXPECT_TRUE(wavefront.values == megakernel.values);
    float depthSum = 0;  // the plane fills the view: every depth is 5
    for (size_t i = 0; i < megakernel.values.size(); i += megakernel.channels.size()) depthSum += megakernel.values[i];
    EXPECT_GT(depthSum, 0.f);
}

// The variance AOV is s² / n of each pixel's own samples: recomputed here from the passes.
TEST(AovRender, VarianceIsTheSampleVarianceOfThePixelMean) {
    TempDir dir;
    auto r = makeRenderer(dir, planeScene(kPath), request("v:variance,d:depth"));
    std::vector<PixelSample> samples;  // every pass's, pixel-major within a pass
    while (!r->finished()) {
        r->step();
        const SamplePass* pass = r->session().lastPass();
        ASSERT_NE(pass, nullptr);
        samples.insert(samples.end(), pass->samples.begin(), pass->samples.end());
    }
    const AovImage a = r->developAovs();
    ASSERT_EQ(a.channels[0], "v.R");
    const int passes = 2, k = 2;
    ASSERT_EQ(samples.size(), size_t(256 * passes * k));
    int nonZero = 0;
    for (int pixel = 0; pixel < 256; ++pixel)
        for (int c = 0; c < 3; ++c) {
            double sum = 0, sumSq = 0;
            for (int p = 0; p < passes; ++p)
                for (int s = 0; s < k; ++s) {
                    const double v = samples[size_t(p * 256 * k + pixel * k + s)].L[c];
                    sum += v;
                    sumSq += v * v;
                }
            const double n = passes * k, mean = sum / n;
            double ss = 0;  // two-pass form, for an independent check
            for (int p = 0; p < passes; ++p)
                for (int s = 0; s < k; ++s) {
                    const double d = samples[size_t(p * 256 * k + pixel * k + s)].L[c] - mean;
                    ss += d * d;
                }
            const double expected = ss / (n - 1) / n;
            const float got = a.at(pixel % 16, pixel / 16, size_t(c));
            EXPECT_NEAR(got, expected, 1e-5 * std::max(1.0, expected))
                << "pixel " << pixel << " channel " << c;
            nonZero += got > 0;
        }
    EXPECT_GT(nonZero, 100);                   // the plane is noisy: the test sees real variances
    EXPECT_NEAR(a.at(3, 3, 3), 4.99f, 1e-5f);  // depth after the variance
}

// mlt, sppm, ppm: the variance AOV by batch means over steps (docs/AOV.md).
RenderRequest batchRequest(const std::string& integrator, int spp, const std::string& aovs = "v:variance") {
    RenderRequest r = request(aovs, integrator == "ppm" ? "sppm" : integrator);
    r.integrator = integrator;
    r.samplesPerPixel = spp;
    if (integrator == "mlt")  // p_large 0: b stays the bootstrap's, so develop() is linear in the steps
        r.integratorParams.push_back({"p_large", IntegratorParam::Kind::Text, "0", "--mlt-large-step"});
    return r;
}

/// Batch estimates from the developed images: the image after k steps is the mean of the k steps'
/// own estimates (sppm: i L_i = Σ Ld + τ / (photons π R²); mlt: splats / their weight, the same
/// weight per step), so step k's is k I_k - (k - 1) I_(k-1). The variance of their mean, s² / n.
std::vector<double> varianceFromDevelopedSteps(Renderer& r) {
    std::vector<std::vector<double>> batches;
    std::vector<double> previous;
    while (!r.finished()) {
        r.step();
        if (!r.session().lastStepEstimate()) continue;  // mlt's bootstrap
        const Image image = r.develop();
        const double k = double(batches.size() + 1);
        std::vector<double> batch(image.rgb.size());
        for (size_t i = 0; i < batch.size(); ++i) {
            const double now = k * double(image.rgb[i]);
            batch[i] = now - (previous.empty() ? 0.0 : (k - 1) * previous[i]);
        }
        previous.assign(image.rgb.begin(), image.rgb.end());
        batches.push_back(std::move(batch));
    }
    const double n = double(batches.size());
    std::vector<double> variance(previous.size());
    for (size_t i = 0; i < variance.size(); ++i) {
        double mean = 0, ss = 0;
        for (const auto& b : batches) mean += b[i] / n;
        for (const auto& b : batches) ss += (b[i] - mean) * (b[i] - mean);
        variance[i] = ss / (n - 1) / n;
    }
    return variance;
}

TEST(AovRender, BatchVarianceEqualsTheDevelopedStepsSpread) {
    TempDir dir;
    // A diffuse sphere beside the light, out of view: photons reach the plane after a bounce
    // (ppm's steps differ in their photons only).
    const std::string bouncer = kPath + R"(<shape type="sphere"><float name="radius" value="1"/>
        <point name="center" x="2" y="0" z="2.5"/><bsdf type="diffuse"/></shape>)";
    for (const char* integrator : {"sppm", "ppm", "mlt"}) {
        SCOPED_TRACE(integrator);
        const int spp = std::string(integrator) == "mlt" ? 1 : 6;  // mlt: 16 iterations of 16 chains
        auto r = makeRenderer(dir, planeScene(bouncer), batchRequest(integrator, spp));
        const std::vector<double> expected = varianceFromDevelopedSteps(*r);
        const AovImage a = r->developAovs();
        ASSERT_EQ(a.channels, (std::vector<std::string>{"v.R", "v.G", "v.B"}));
        const Image image = r->develop();
        int positive = 0;
        for (size_t i = 0; i < expected.size(); ++i) {
            const double mean = image.rgb[i];
            ASSERT_NEAR(a.values[i], expected[i], 1e-4 * expected[i] + 1e-5 * mean * mean + 1e-12) << "value " << i;
            positive += a.values[i] > 0;
        }
        EXPECT_GT(positive, 60);  // real spreads, not zeros
    }
}

TEST(AovRender, BatchVarianceFallsAsOneOverTheSteps) {
    // alpha 1: sppm's radius stays put, so its iterations are independent, identically
    // distributed estimates and the variance of their mean falls as 1/n.
    TempDir dir;
    auto meanVariance = [&](int iterations) {
        RenderRequest r = batchRequest("sppm", iterations);
        r.integratorParams.push_back({"alpha", IntegratorParam::Kind::Text, "1", "--sppm-alpha"});
        const AovImage a = renderAovs(dir, planeScene(kPath), r);
        double sum = 0;
        for (float v : a.values) sum += v;
        return sum / double(a.values.size());
    };
    const double ratio = meanVariance(8) / meanVariance(32);
    EXPECT_GT(ratio, 2.5);
    EXPECT_LT(ratio, 6.5);
}

TEST(AovRender, BatchVarianceIsZeroWhereTheEstimateIsDeterministic) {
    // The plane covers x > 0.5 of the view [-1, 1]: pixel columns 0-11 see nothing, every step.
    TempDir dir;
    for (const char* integrator : {"sppm", "mlt"}) {
        SCOPED_TRACE(integrator);
        const AovImage a = renderAovs(dir, planeScene(kPath, 2.5f), batchRequest(integrator, 4));
        int lit = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (size_t c = 0; c < 3; ++c) {
                    if (x < 12) {
                        EXPECT_EQ(a.at(x, y, c), 0.0f) << x << "," << y;
                    }
                    lit += x >= 13 && a.at(x, y, c) > 0;
                }
        EXPECT_GT(lit, 20);
    }
}

TEST(AovRender, BatchVarianceOfFewerThanTwoStepsIsNaNAndNoDenoiserGuide) {
    TempDir dir;
    for (const char* integrator : {"sppm", "mlt"}) {
        SCOPED_TRACE(integrator);
        auto r = makeRenderer(dir, planeScene(kPath), batchRequest(integrator, 4, "v:variance,d:depth"));
        r->step();
        if (std::string(integrator) == "mlt") r->step();  // the bootstrap, then one batch
        const AovImage a = r->developAovs();
        for (int p = 0; p < 256; ++p) {
            for (size_t c = 0; c < 3; ++c) ASSERT_TRUE(std::isnan(a.values[size_t(p) * 4 + c]));
            ASSERT_NEAR(a.values[size_t(p) * 4 + 3], 4.99f, 1e-5f);  // depth is defined
        }
        const DenoiseFeatures f = featuresFromAovs(a);
        EXPECT_FALSE(f.variance.has_value());  // NL-means estimates its own
        EXPECT_TRUE(f.depth.has_value());
        r->step();
        EXPECT_TRUE(featuresFromAovs(r->developAovs()).variance.has_value());
    }
}

TEST(AovRender, SameAovsForOneAndTwoThreads) {
    TempDir dir;
    auto aovs = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        return renderAovs(dir, planeScene(kPath),
                          request(std::string(kAllGeometric) + ",v:variance"));
    };
    EXPECT_TRUE(aovs(1).values == aovs(2).values);
    for (const char* integrator : {"sppm", "mlt"}) {
        SCOPED_TRACE(integrator);
        auto batches = [&](int threads) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
            return renderAovs(dir, planeScene(kPath), batchRequest(integrator, 4));
        };
        EXPECT_TRUE(batches(1).values == batches(2).values);
    }
}

TEST(AovRender, ResumeKeepsTheAovsAndRefusesOtherOnes) {
    TempDir dir;
    const std::string aovs = "d:depth,p:position,v:variance";
    for (const char* integrator : {"path", "sppm", "mlt"}) {
        SCOPED_TRACE(integrator);
        const std::string list = aovs;
        const AovImage whole = renderAovs(dir, planeScene(kPath), request(list, integrator));
        auto first = makeRenderer(dir, planeScene(kPath), request(list, integrator));
        // mlt: the bootstrap and two iterations (batches) before the checkpoint.
        for (int i = 0; i < (std::string(integrator) == "mlt" ? 3 : 1); ++i) first->step();
        const std::string ckpt = dir.path("r.ckpt");
        first->save(ckpt);
        auto resumed = makeRenderer(dir, planeScene(kPath), request(list, integrator));
        resumed->load(ckpt);
        while (!resumed->finished()) resumed->step();
        EXPECT_TRUE(resumed->developAovs().values == whole.values);
        // Other AOVs, or none, do not resume this checkpoint.
        auto other = makeRenderer(dir, planeScene(kPath), request("d:depth", integrator));
        EXPECT_THROW(other->load(ckpt), Error);
        auto none = makeRenderer(dir, planeScene(kPath), request("", integrator));
        EXPECT_THROW(none->load(ckpt), Error);
    }
}

TEST(AovRender, ExrOutputHoldsTheLayersAndPngTheImage) {
    TempDir dir;
    auto r = makeRenderer(dir, planeScene(kPath), request("dd.y:depth,nn:sh_normal,v:variance"));
    while (!r->finished()) r->step();
    const Image image = r->develop();
    writeRenderImages({dir.path("out.exr"), dir.path("out.png")}, image, *r);
    const ExrLayers read = readExrLayers(dir.path("out.exr"));
    EXPECT_TRUE(read.image.rgb == image.rgb);
    EXPECT_EQ(read.metadata.entries.at("caustica.aovs"), "dd.y:depth,nn:sh_normal,v:variance");
    const AovImage aovs = r->developAovs();
    EXPECT_EQ(read.aovs.channels, aovs.channels);
    EXPECT_TRUE(read.aovs.values == aovs.values);
    EXPECT_TRUE(readExrLayers(dir.path("out.png")).aovs.empty());
}

// Mitsuba's aov integrator: the nested integrator renders, the list travels with it.
TEST(AovScene, MitsubaAovIntegratorKeepsItsNestedIntegrator) {
    TempDir dir;
    std::vector<std::string> warnings;
    const Scene scene =
        loadXml(dir,
                sceneXml("<integrator type=\"aov\">\n"
                         "<string name=\"aovs\" value=\"dd.y:depth,nn:sh_normal\"/>\n"
                         "<integrator type=\"direct\" name=\"my_image\">\n"
                         "<integer name=\"emitter_samples\" value=\"2\"/></integrator>\n"
                         "<integrator type=\"path\" name=\"second\"/>\n"
                         "</integrator>"),
                &warnings);
    EXPECT_EQ(scene.integrator.type, "direct");
    EXPECT_EQ(integratorParam(scene, "emitter_samples"), "2");
    EXPECT_EQ(scene.integrator.aovs, "dd.y:depth,nn:sh_normal");
    EXPECT_NE(scene.integrator.aovsWhere.find("scene.xml:4"), std::string::npos);
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:7:", "'path' is not used"}));
    // The scene's list makes the render's AOVs.
    auto r = std::make_unique<Renderer>(loadXml(dir, planeScene(R"(<integrator type="aov">
        <string name="aovs" value="dd.y:depth"/><integrator type="path" name="my_image"/></integrator>)")),
                                        request(""));
    EXPECT_TRUE(r->hasAovs());
    EXPECT_EQ(r->developAovs().channels, std::vector<std::string>{"dd.y.T"});
}

TEST(AovScene, BadListsAreRefusedWithTheirLine) {
    TempDir dir;
    expectError(
        [&] {
            loadXml(
                dir,
                sceneXml("<integrator type=\"aov\">\n<string name=\"aovs\" value=\"dd.y:dpth\"/>\n"
                         "<integrator type=\"path\"/></integrator>"));
        },
        "scene.xml", 4, "unknown AOV type 'dpth'");
    expectError(
        [&] {
            loadXml(dir,
                    sceneXml("<integrator type=\"aov\">\n<string name=\"aovs\" value=\"depth\"/>\n"
                             "<integrator type=\"path\"/></integrator>"));
        },
        "scene.xml", 4, "not a NAME:TYPE pair");
    expectError([&] { makeRenderer(dir, planeScene(kPath), request("d:normal")); }, "--aov", 0,
                "unknown AOV type 'normal'");
}

}  // namespace
}  // namespace caustica::test
