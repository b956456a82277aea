// stereo_render_test.cpp — stereo renders through the render session (scene/stereo_rig.h): each
// eye of a stereo render equals a mono render of that eye's camera at the eye's seed (path in both
// execution modes, direct, sppm's left eye: one shared photon pass), MLT's chains cover both
// eyes, the rig is part of the checkpoint's identity, and the stereo outputs (multi-view EXR,
// separate EXRs, anaglyph) read back as the two halves of the image. AOVs: each eye's equal a
// mono render's of that eye, go into each view of the outputs, and --denoise works eye by eye.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/exr_multiview.h"
#include "caustica/io/image_io.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/render_denoise.h"
#include "caustica/render/render_outputs.h"
#include "caustica/render/render_run.h"
#include "caustica/render/renderer.h"
#include "caustica/render/stereo_outputs.h"
#include "caustica/scene/stereo_rig.h"
#include "caustica/util/error.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

// Two spheres at different depths over a lit quad; a gaussian filter, so that the seam matters.
constexpr const char* kSceneXml = R"(<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="8"/>
            <rfilter type="gaussian"/></film>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"/></shape>
    <shape type="sphere"><float name="radius" value="0.3"/><point name="center" x="-0.4" y="0" z="1"/>
        <bsdf type="diffuse"/></shape>
    <shape type="sphere"><float name="radius" value="0.2"/><point name="center" x="0.5" y="0.3" z="0.4"/>
        <emitter type="area"><rgb name="radiance" value="6"/></emitter></shape>
</scene>
)";
constexpr int kEyeWidth = 12, kHeight = 8;
constexpr uint64_t kSeed = 7;

class StereoRender : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("caustica_stereo_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        std::ofstream(path("scene.xml")) << kSceneXml;
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    static RenderRequest request(const std::string& integrator, int spp = 4) {
        RenderRequest r;
        r.integrator = integrator;
        r.device = "cpu";
        r.samplesPerPixel = spp;
        r.samplesPerPass = 2;
        r.seed = kSeed;
        if (integrator == "sppm")
            r.integratorParams = {{"photon_count", IntegratorParam::Kind::Text, "2000", "--sppm-photons"},
                                  {"initial_radius", IntegratorParam::Kind::Text, "0.05", "--sppm-radius"}};
        if (integrator == "mlt")
            r.integratorParams = {{"chains", IntegratorParam::Kind::Text, "32", "--mlt-chains"},
                                  {"luminance_samples", IntegratorParam::Kind::Text, "4096", "--mlt-bootstrap"},
                                  {"splat", IntegratorParam::Kind::Text, "sort", "--splat"}};
        return r;
    }
    static StereoSettings stereo(StereoMode mode) { return StereoSettings{mode, 0.1f, 1.5f}; }
    static std::unique_ptr<Renderer> finished(Scene scene, const RenderRequest& r) {
        auto renderer = std::make_unique<Renderer>(std::move(scene), r);
        while (!renderer->finished()) renderer->step();
        return renderer;
    }
    std::unique_ptr<Renderer> renderer(const RenderRequest& r) const { return finished(loadScene(path("scene.xml")), r); }
    Image render(const RenderRequest& r) const { return renderer(r)->develop(); }
    /// A mono render from eye `eye`'s camera at that eye's seed.
    std::unique_ptr<Renderer> monoEyeRenderer(RenderRequest r, const StereoSettings& s, int eye) const {
        Scene scene = loadScene(path("scene.xml"));
        Scene rigged = scene;
        applyStereo(rigged, s);
        scene.camera = eyeCamera(rigged.camera, eye);
        r.seed = stereoEyeSeed(kSeed, eye);
        return finished(std::move(scene), r);
    }
    Image monoEye(const RenderRequest& r, const StereoSettings& s, int eye) const {
        return monoEyeRenderer(r, s, eye)->develop();
    }
    /// The AOVs of one eye against a mono render's: the left eye bit for bit, the right eye up to
    /// the rounding of its film positions (expectEyeEquals).
    static void expectEyeAovsEqual(const AovImage& stereoAovs, const AovImage& mono, int eye) {
        const AovImage eyeAovs = stereoEyeAovs(stereoAovs, eye);
        ASSERT_EQ(eyeAovs.width, mono.width);
        ASSERT_EQ(eyeAovs.channels, mono.channels);
        ASSERT_EQ(eyeAovs.values.size(), mono.values.size());
        for (size_t i = 0; i < mono.values.size(); ++i) {
            if (eye == 0)
                ASSERT_EQ(eyeAovs.values[i], mono.values[i]) << "eye 0 value " << i;
            else
                ASSERT_NEAR(eyeAovs.values[i], mono.values[i], 1e-4f * std::max(std::abs(mono.values[i]), 1.0f))
                    << "eye 1 value " << i << " (" << mono.channels[i % mono.channels.size()] << ")";
        }
    }
    /// The left eye bit for bit; the right eye up to rounding: its film positions are x + W +
    /// jitter, rounded to the float grid near x + W, the mono render's to the grid near x.
    static void expectEyeEquals(const Image& stereoImage, const Image& mono, int eye) {
        ASSERT_EQ(stereoImage.width, 2 * kEyeWidth);
        ASSERT_EQ(mono.width, kEyeWidth);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kEyeWidth; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float a = stereoImage.pixel(x + eye * kEyeWidth, y)[c], b = mono.pixel(x, y)[c];
                    if (eye == 0)
                        ASSERT_EQ(a, b) << "eye 0 pixel " << x << "," << y;
                    else
                        ASSERT_NEAR(a, b, 1e-4f * std::max(b, 1e-2f)) << "eye 1 pixel " << x << "," << y;
                }
    }
    static double eyeMean(const Image& image, int eye) {
        double sum = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kEyeWidth; ++x) sum += image.at(x + eye * kEyeWidth, y).luminance();
        return sum / (kEyeWidth * kHeight);
    }

    fs::path dir_;
};

TEST_F(StereoRender, EachEyeEqualsAMonoRenderOfThatEye) {
    for (const char* integrator : {"path", "direct"})
        for (StereoMode mode : {StereoMode::OffAxis, StereoMode::Parallel, StereoMode::ToeIn}) {
            RenderRequest r = request(integrator);
            r.stereo = stereo(mode);
            const Image both = render(r);
            RenderRequest m = request(integrator);
            for (int eye = 0; eye < 2; ++eye) expectEyeEquals(both, monoEye(m, r.stereo, eye), eye);
        }
    RenderRequest wavefront = request("path");
    wavefront.pathMode = "wavefront";
    wavefront.stereo = stereo(StereoMode::OffAxis);
    const Image both = render(wavefront);
    for (int eye = 0; eye < 2; ++eye) expectEyeEquals(both, monoEye(request("path"), wavefront.stereo, eye), eye);
}

TEST_F(StereoRender, SppmEyesShareOnePhotonPass) {
    // The photon streams depend on the render's seed only, so the left eye (which keeps that seed)
    // is exactly the mono left-eye render; the right eye sees the same photons.
    RenderRequest r = request("sppm", 3);
    r.stereo = stereo(StereoMode::OffAxis);
    const Image both = render(r);
    expectEyeEquals(both, monoEye(request("sppm", 3), r.stereo, 0), 0);
    EXPECT_GT(eyeMean(both, 1), 0.0);
}

TEST_F(StereoRender, MltChainsCoverBothEyes) {
    RenderRequest r = request("mlt", 512);
    r.stereo = stereo(StereoMode::OffAxis);
    const Image mlt = render(r);
    RenderRequest p = request("path", 256);
    p.stereo = r.stereo;
    const Image path = render(p);
    for (int eye = 0; eye < 2; ++eye) {
        EXPECT_GT(eyeMean(mlt, eye), 0.0);
        EXPECT_NEAR(eyeMean(mlt, eye) / eyeMean(path, eye), 1.0, 0.1) << "eye " << eye;
    }
}

// MLT's relative target blurs the bootstrap's brightness within each eye (mlt_target.h; here
// beside the other stereo tests, which build the integrators already).
TEST(StereoMltTarget, BlurStaysInEachEye) {
    constexpr int w = 8, h = 4;
    std::vector<float> luminance;
    std::vector<uint32_t> pixel;
    for (uint32_t p = 0; p < uint32_t(2 * w * h); ++p)
        for (int k = 0; k < 4; ++k) {
            luminance.push_back(int(p % (2 * w)) < w ? 1.0f : 10.0f);  // the right eye brighter
            pixel.push_back(p);
        }
    const std::vector<float> seam = mltRelativePixelWeights(luminance.data(), pixel.data(), luminance.size(), 2 * w,
                                                            h, 1, w);
    const std::vector<float> joined =
        mltRelativePixelWeights(luminance.data(), pixel.data(), luminance.size(), 2 * w, h, 1, 0);
    // With the seam each eye is uniform, so its weights are too; without it the right eye's
    // columns next to the seam are blurred with the dark left eye (a larger weight 1 / B).
    for (int y = 0; y < h; ++y) {
        EXPECT_EQ(seam[size_t(y * 2 * w + w)], seam[size_t(y * 2 * w + 2 * w - 1)]);
        EXPECT_EQ(seam[size_t(y * 2 * w)], seam[size_t(y * 2 * w + w - 1)]);
        EXPECT_GT(joined[size_t(y * 2 * w + w)], joined[size_t(y * 2 * w + 2 * w - 1)]);
    }
}

TEST_F(StereoRender, TheRigIsPartOfTheCheckpointIdentity) {
    RenderRequest r = request("path");
    r.stereo = stereo(StereoMode::OffAxis);
    Renderer first(loadScene(path("scene.xml")), r);
    first.step();
    first.save(path("a.ckpt"));
    for (StereoSettings other : {StereoSettings{StereoMode::OffAxis, 0.2f, 1.5f},
                                 StereoSettings{StereoMode::OffAxis, 0.1f, 2.0f},
                                 StereoSettings{StereoMode::ToeIn, 0.1f, 1.5f}}) {
        RenderRequest changed = r;
        changed.stereo = other;
        Renderer second(loadScene(path("scene.xml")), changed);
        try {
            second.load(path("a.ckpt"));
            ADD_FAILURE() << "resumed with another rig";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("stereo differs"), std::string::npos) << e.what();
        }
    }
    // A mono render cannot resume it either (nor the reverse): the film size differs first.
    Renderer mono(loadScene(path("scene.xml")), request("path"));
    EXPECT_THROW(mono.load(path("a.ckpt")), Error);
    mono.step();
    mono.save(path("mono.ckpt"));
    Renderer again(loadScene(path("scene.xml")), r);
    EXPECT_THROW(again.load(path("mono.ckpt")), Error);
}

TEST_F(StereoRender, OutputsReadBackAsTheTwoEyes) {
    RenderRequest r = request("path", 2);
    r.stereo = stereo(StereoMode::OffAxis);
    RunControl c;
    c.outputs = {path("pair.exr"), path("pair.png")};
    c.quiet = true;
    c.catchInterrupts = false;
    c.stereo.enabled = true;
    c.stereo.anaglyph = path("pair.anaglyph.png");
    prepareRun(c);
    Renderer renderer(loadScene(path("scene.xml")), r);
    const RunResult result = runRender(renderer, c);
    const Image image = renderer.develop();
    ASSERT_EQ(result.written.size(), 3u);
    const StereoImagePair views = readMultiViewExr(path("pair.exr"));
    expectEyeEquals(image, views.left, 0);
    expectEyeEquals(image, views.right, 1);
    EXPECT_EQ(readImage(path("pair.png")).width, 2 * kEyeWidth);  // side by side
    // Anaglyph: red from the left eye, green and blue from the right (8-bit sRGB, read back linear).
    const Image anaglyph = readImage(path("pair.anaglyph.png"));
    ASSERT_EQ(anaglyph.width, kEyeWidth);
    const Image expected = anaglyphImage(image);
    for (size_t i = 0; i < expected.rgb.size(); ++i) {
        const float want = std::min(expected.rgb[i], 1.0f);
        EXPECT_NEAR(anaglyph.rgb[i], want, 0.01f + 0.02f * want) << i;
    }
    for (size_t p = 0; p < expected.pixelCount(); ++p) {
        EXPECT_EQ(expected.rgb[3 * p], views.left.rgb[3 * p]);
        EXPECT_EQ(expected.rgb[3 * p + 1], views.right.rgb[3 * p + 1]);
        EXPECT_EQ(expected.rgb[3 * p + 2], views.right.rgb[3 * p + 2]);
    }

    // Separate files: NAME.left.exr and NAME.right.exr.
    RunControl s = c;
    s.outputs = {path("eyes.exr")};
    s.stereo.separate = true;
    s.stereo.anaglyph.clear();
    Renderer second(loadScene(path("scene.xml")), r);
    const RunResult written = runRender(second, s);
    EXPECT_EQ(written.written, (std::vector<std::string>{path("eyes.left.exr"), path("eyes.right.exr")}));
    expectEyeEquals(image, readImage(path("eyes.left.exr")), 0);
    expectEyeEquals(image, readImage(path("eyes.right.exr")), 1);
    EXPECT_FALSE(fs::exists(path("eyes.exr")));
}

TEST_F(StereoRender, BadStereoOutputsAreRefusedBeforeRendering) {
    RunControl c;
    c.outputs = {path("pair.exr")};
    c.stereo.enabled = true;
    c.stereo.anaglyph = path("pair.jpg");
    EXPECT_THROW(prepareRun(c), Error);
    c.stereo.anaglyph = path("missing/pair.png");
    EXPECT_THROW(prepareRun(c), Error);
    c.stereo.anaglyph.clear();
    c.stereo.separate = true;
    c.outputs = {path("missing/pair.exr")};
    EXPECT_THROW(prepareRun(c), Error);
    // Stereo outputs for a mono render (or the reverse) are refused, not written wrongly.
    Renderer mono(loadScene(path("scene.xml")), request("path", 1));
    mono.step();
    RunControl s;
    s.outputs = {path("x.exr")};
    s.stereo.enabled = true;
    EXPECT_THROW(writeRenderImages(s.outputs, mono.develop(), mono, s.stereo), Error);
}

TEST_F(StereoRender, EachEyesAovsEqualAMonoRenderOfThatEye) {
    // path: the AOV pass traces the pass's camera samples (variance included); sppm: one AOV
    // sample per step (variance over its steps), the left eye exactly.
    const char* const aovs = "dd:depth,nn:sh_normal,pp:position,a:albedo,s:shape_index,v:variance";
    for (StereoMode mode : {StereoMode::OffAxis, StereoMode::ToeIn}) {
        RenderRequest r = request("path");
        r.aovs = aovs;
        r.stereo = stereo(mode);
        const AovImage both = renderer(r)->developAovs();
        ASSERT_EQ(both.width, 2 * kEyeWidth);
        RenderRequest m = request("path");
        m.aovs = aovs;
        for (int eye = 0; eye < 2; ++eye) expectEyeAovsEqual(both, monoEyeRenderer(m, r.stereo, eye)->developAovs(), eye);
    }
    // sppm's variance by batch means over its iterations: the left eye's too.
    RenderRequest r = request("sppm", 3);
    r.aovs = "dd:depth,nn:sh_normal,v:variance";
    r.stereo = stereo(StereoMode::OffAxis);
    const AovImage both = renderer(r)->developAovs();
    RenderRequest m = request("sppm", 3);
    m.aovs = r.aovs;
    expectEyeAovsEqual(both, monoEyeRenderer(m, r.stereo, 0)->developAovs(), 0);
}

TEST_F(StereoRender, AovsGoIntoEachViewOfTheOutputs) {
    RenderRequest r = request("path", 2);
    r.aovs = "dd.y:depth,nn:sh_normal";
    r.stereo = stereo(StereoMode::OffAxis);
    RunControl c;
    c.outputs = {path("pair.exr")};
    c.quiet = true;
    c.catchInterrupts = false;
    c.stereo.enabled = true;
    prepareRun(c);
    Renderer multiView(loadScene(path("scene.xml")), r);
    runRender(multiView, c);
    const AovImage aovs = multiView.developAovs();
    const StereoImagePair views = readMultiViewExr(path("pair.exr"));
    ASSERT_EQ(views.leftAovs.spec.text(), "dd.y:depth,nn:sh_normal");
    EXPECT_TRUE(views.leftAovs.values == stereoEyeAovs(aovs, 0).values);
    EXPECT_TRUE(views.rightAovs.values == stereoEyeAovs(aovs, 1).values);
    EXPECT_NE(views.leftAovs.values, views.rightAovs.values);

    // Separate files: each eye's file is a mono render's layered EXR.
    c.outputs = {path("eyes.exr")};
    c.stereo.separate = true;
    Renderer separate(loadScene(path("scene.xml")), r);
    runRender(separate, c);
    for (int eye = 0; eye < 2; ++eye) {
        const ExrLayers layers = readExrLayers(path(eye == 0 ? "eyes.left.exr" : "eyes.right.exr"));
        EXPECT_EQ(layers.aovs.channels, aovs.channels);
        EXPECT_TRUE(layers.aovs.values == stereoEyeAovs(aovs, eye).values) << "eye " << eye;
        expectEyeEquals(separate.develop(), layers.image, eye);
    }
}

TEST_F(StereoRender, DenoiseWorksEyeByEye) {
    RenderRequest r = request("path", 4);
    r.stereo = stereo(StereoMode::OffAxis);
    r.denoiseGuides = true;
    RunControl c;
    c.outputs = {path("pair.exr"), path("pair.png")};
    c.quiet = true;
    c.catchInterrupts = false;
    c.stereo.enabled = true;
    c.denoise = DenoiseSettings{};
    prepareRun(c);
    Renderer renderer(loadScene(path("scene.xml")), r);
    const RunResult result = runRender(renderer, c);
    EXPECT_EQ(result.written, (std::vector<std::string>{path("pair.exr"), path("pair.png"), path("pair.denoised.exr"),
                                                        path("pair.denoised.png")}));
    // Each eye is denoised alone with its own guides: what a mono render of the eye would get.
    const Image image = renderer.develop();
    const AovImage aovs = renderer.developAovs();
    const StereoImagePair denoised = readMultiViewExr(path("pair.denoised.exr"));
    for (int eye = 0; eye < 2; ++eye) {
        const Image expected =
            denoise(stereoEyeImage(image, eye), featuresFromAovs(stereoEyeAovs(aovs, eye)), *c.denoise);
        EXPECT_TRUE((eye == 0 ? denoised.left : denoised.right).rgb == expected.rgb) << "eye " << eye;
    }
    EXPECT_EQ(readImage(path("pair.denoised.png")).width, 2 * kEyeWidth);
    // The denoised eye files are checked before rendering too.
    c.stereo.separate = true;
    c.outputs = {path("eyes.exr")};
    fs::create_directories(path("eyes.denoised.right.exr"));
    EXPECT_THROW(prepareRun(c), Error);
}

}  // namespace
}  // namespace caustica::test
