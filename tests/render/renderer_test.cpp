// The render session (render/renderer.h): budgets across resumes, checkpoints that restore a
// render bit for bit, and resumes refused for every setting that changes the image.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "caustica/accel/embree_accel.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/renderer.h"
#include "caustica/util/error.h"

namespace caustica::test {
namespace {

namespace fs = std::filesystem;

// A small scene of its own (so that the tests can edit it): a quad lit by an area light, the
// quad an OBJ file beside the XML.
constexpr const char* kSceneXml = R"(<scene version="3.0.0">
    <default name="width" value="12"/>
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="$width"/><integer name="height" value="8"/>
            <rfilter type="box"/></film>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    </sensor>
    <shape type="obj"><string name="filename" value="quad.obj"/></shape>
    <shape type="sphere"><float name="radius" value="0.3"/><point name="center" x="0" y="0" z="1"/>
        <emitter type="area"><rgb name="radiance" value="4"/></emitter></shape>
</scene>
)";
constexpr const char* kQuadObj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

class RendererTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("caustica_renderer_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        writeFile("scene.xml", kSceneXml);
        writeFile("quad.obj", kQuadObj);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    void writeFile(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
    std::string readFile(const std::string& name) const {
        std::ifstream in(path(name), std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
    std::unique_ptr<Renderer> renderer(RenderRequest request, std::map<std::string, std::string> defines = {}) const {
        request.device = "cpu";
        request.defines = defines;
        return std::make_unique<Renderer>(loadScene(path("scene.xml"), defines), request);
    }
    static RenderRequest passes(int spp) {
        RenderRequest r;
        r.samplesPerPixel = spp;
        r.samplesPerPass = 1;
        r.seed = 7;
        return r;
    }
    static RenderRequest mlt(int mutationsPerPixel) {
        RenderRequest r = passes(mutationsPerPixel);
        r.integrator = "mlt";
        r.integratorParams = {{"chains", IntegratorParam::Kind::Text, "16", "--mlt-chains"},
                              {"luminance_samples", IntegratorParam::Kind::Text, "512", "--mlt-bootstrap"},
                              {"splat", IntegratorParam::Kind::Text, "sort", "--splat"}};  // bit-reproducible
        return r;
    }
    static void finish(Renderer& r) {
        while (!r.finished()) r.step();
    }

    fs::path dir_;
};

void expectSameImage(const Image& a, const Image& b) {
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_TRUE(a.rgb == b.rgb) << "the images differ";
}

/// Embree reads the vertices in place only where the positions have a spare vertex of capacity:
/// the loader gives them one, and so does the Renderer to a Scene copied without it (Python).
TEST_F(RendererTest, SceneKeepsTheVertexPaddingEmbreeShares) {
    const Scene loaded = loadScene(path("scene.xml"));
    EXPECT_TRUE(sharesVertexArray(loaded.positions));
    Scene copy = loaded;
    copy.positions = std::vector<Vec3f>(loaded.positions.begin(), loaded.positions.end());
    RenderRequest request = passes(1);
    request.device = "cpu";
    request.accel = AccelKind::Embree;
    const Renderer r(std::move(copy), request);
    EXPECT_TRUE(sharesVertexArray(r.scene().positions));
    EXPECT_TRUE(r.scene().positions == loaded.positions);
}

TEST_F(RendererTest, ResumedRendersEndWithTheUninterruptedImage) {
    for (const RenderRequest& request : {passes(6), mlt(6)}) {
        SCOPED_TRACE(request.integrator.empty() ? "path" : request.integrator);
        auto whole = renderer(request);
        finish(*whole);
        auto first = renderer(request);
        for (int i = 0; i < 3; ++i) first->step();
        first->save(path("r.ckpt"));
        auto resumed = renderer(request);
        resumed->load(path("r.ckpt"));
        EXPECT_EQ(resumed->progress().samplesPerPixel, first->progress().samplesPerPixel);
        finish(*resumed);
        expectSameImage(resumed->develop(), whole->develop());
        EXPECT_EQ(resumed->progress().samplesPerPixel, whole->progress().samplesPerPixel);
    }
}

TEST_F(RendererTest, BudgetsCountTheWholeRender) {
    auto first = renderer(passes(8));
    for (int i = 0; i < 3; ++i) first->step();
    first->save(path("r.ckpt"));
    const double firstSeconds = first->progress().seconds;
    ASSERT_GT(firstSeconds, 0);

    // The sample budget: the resumed render renders the 5 samples per pixel left, not 8 more.
    auto resumed = renderer(passes(8));
    resumed->load(path("r.ckpt"));
    EXPECT_DOUBLE_EQ(resumed->progress().seconds, firstSeconds) << "the time so far comes from the checkpoint";
    int steps = 0;
    for (; !resumed->finished(); ++steps) resumed->step();
    EXPECT_EQ(steps, 5);
    EXPECT_EQ(resumed->stats().samplesPerPixel, 8);
    EXPECT_GT(resumed->stats().seconds, firstSeconds);
    EXPECT_LT(resumed->runSeconds(), resumed->stats().seconds);

    // The time budget: a limit the first run has already spent leaves nothing to do.
    RenderRequest timed = passes(0);
    timed.timeLimit = firstSeconds / 2;
    auto spent = renderer(timed);
    spent->load(path("r.ckpt"));
    EXPECT_TRUE(spent->finished());
}

TEST_F(RendererTest, ResumeWithAnySettingThatChangesTheImageIsRefused) {
    auto saved = renderer(passes(4));
    saved->step();
    saved->save(path("r.ckpt"));
    const std::string bytes = readFile("r.ckpt");

    auto expectRefused = [&](Renderer& r, const std::string& what) {
        SCOPED_TRACE(what);
        try {
            r.load(path("r.ckpt"));
            ADD_FAILURE() << "the resume was not refused";
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(path("r.ckpt") + ": ", 0), 0u) << message;
            EXPECT_NE(message.find(what), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
        EXPECT_EQ(readFile("r.ckpt"), bytes) << "a refused resume must leave the checkpoint untouched";
        EXPECT_EQ(r.progress().samplesPerPixel, 0) << "a refused resume must leave the render untouched";
    };

    RenderRequest seed = passes(4);
    seed.seed = 8;
    expectRefused(*renderer(seed), "seed differs (written for 7; now 8)");
    RenderRequest res = passes(4);
    res.resolution = std::make_pair(6, 4);
    expectRefused(*renderer(res), "resolution differs (written for 12x8; now 6x4)");
    expectRefused(*renderer(passes(4), {{"width", "12"}}), "-D values differs (written for none; now width=12)");
    RenderRequest direct = passes(4);
    direct.integrator = "direct";
    expectRefused(*renderer(direct), "integrator differs (written for path; now direct)");

    writeFile("quad.obj", std::string(kQuadObj) + "# edited\n");
    expectRefused(*renderer(passes(4)), "input file differs (written for " + path("quad.obj") + ", sha ");
    writeFile("quad.obj", kQuadObj);

    std::string edited = kSceneXml;
    edited.replace(edited.find("value=\"4\"/></integrator>"), 9, "value=\"5\"");
    writeFile("scene.xml", edited);
    expectRefused(*renderer(passes(4)), "scene file differs (written for " + path("scene.xml") + ", sha ");
    writeFile("scene.xml", kSceneXml);

    // The same render resumes; device, ray tracer and execution mode do not change the image.
    RenderRequest other = passes(4);
    other.accel = AccelKind::Bvh;
    other.pathMode = "wavefront";
    auto same = renderer(other);
    EXPECT_NO_THROW(same->load(path("r.ckpt")));
    EXPECT_EQ(same->progress().samplesPerPixel, 1);
}

TEST_F(RendererTest, IntegratorParametersAreComparedByValue) {
    auto saved = renderer(mlt(2));
    saved->step();
    saved->save(path("m.ckpt"));
    RenderRequest other = mlt(2);
    other.integratorParams.push_back({"p_large", IntegratorParam::Kind::Text, "0.3", "--mlt-large-step"});
    try {
        renderer(other)->load(path("m.ckpt"));
        ADD_FAILURE() << "the resume was not refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("p_large differs (written for 0.1; now 0.3)"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(RendererTest, DamagedOrForeignCheckpointsAreRefused) {
    auto saved = renderer(passes(4));
    saved->step();
    saved->save(path("r.ckpt"));
    std::string bytes = readFile("r.ckpt");
    auto expectRefused = [&](const std::string& content, const std::string& what) {
        SCOPED_TRACE(what);
        writeFile("bad.ckpt", content);
        auto r = renderer(passes(4));
        try {
            r->load(path("bad.ckpt"));
            ADD_FAILURE() << "not refused";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(path("bad.ckpt") + ": "), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    expectRefused("CAUSCKP1 an old path checkpoint", "not a caustica checkpoint of this version");
    std::string flipped = bytes;
    flipped[40] ^= 0x10;
    expectRefused(flipped, "damaged");
    expectRefused(bytes.substr(0, bytes.size() - 100), "truncated");
    expectRefused("", "not a caustica checkpoint");
}

TEST_F(RendererTest, SceneWithoutEmitterWarns) {
    std::string dark = kSceneXml;
    dark.erase(dark.find("<emitter"), dark.find("</emitter>") + 10 - dark.find("<emitter"));
    writeFile("scene.xml", dark);
    EXPECT_NE(renderer(passes(1))->warnings().at(0).find("no emitter: the image will be black"), std::string::npos);
}

}  // namespace
}  // namespace caustica::test
