// integrator_settings_test.cpp — the integrators' settings read from a scene's <integrator>
// (io/ keeps it as written, each integrator reads its own): direct's parameters (Mitsuba 3's
// direct.cpp defaults and errors), the path tracer's, MLT's with its command-line options, and
// the mapping of unsupported Mitsuba integrators to the nearest caustica one, with a warning
// naming file:line, the original and the replacement.
#include "caustica/integrators/direct/direct_settings.h"
#include "caustica/integrators/mlt/mlt_settings.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/render/renderer.h"
#include "io/scene_test_util.h"

namespace caustica::test {
namespace {

/// A scene with `integrator`; the load's warnings and the unread parameters' go to `warnings`.
struct Loaded {
    Scene scene;
    std::vector<std::string> warnings;
};

Loaded load(const std::string& integrator) {
    TempDir dir;
    Loaded l;
    l.scene = loadXml(dir, sceneXml(integrator), &l.warnings);
    return l;
}

template <class Settings, class Read>
Settings readSettings(Loaded& l, Read read, const std::vector<IntegratorParam>& commandLine = {}) {
    IntegratorParams params(l.scene.integrator, commandLine);
    const Settings s = read(params);
    for (std::string& w : params.unread()) l.warnings.push_back(std::move(w));
    return s;
}

DirectSettings directOf(Loaded& l) { return readSettings<DirectSettings>(l, readDirectSettings); }
PathSettings pathOf(Loaded& l) { return readSettings<PathSettings>(l, readPathSettings); }

TEST(Integrator, DirectDefaults) {
    Loaded l = load(R"(<integrator type="direct"/>)");
    EXPECT_EQ(l.scene.integrator.type, "direct");
    const DirectSettings d = directOf(l);
    EXPECT_EQ(d.emitterSamples, 1);
    EXPECT_EQ(d.bsdfSamples, 1);
    EXPECT_FALSE(d.hideEmitters);
    EXPECT_TRUE(l.warnings.empty());
}

TEST(Integrator, DirectSampleCounts) {
    Loaded l = load(R"(<integrator type="direct"><integer name="emitter_samples" value="3"/>
        <integer name="bsdf_samples" value="0"/><boolean name="hide_emitters" value="true"/>
        </integrator>)");
    DirectSettings d = directOf(l);
    EXPECT_EQ(d.emitterSamples, 3);
    EXPECT_EQ(d.bsdfSamples, 0);
    EXPECT_TRUE(d.hideEmitters);
    // shading_samples sets both; a count not given takes shading_samples' value (default 1).
    l = load(R"(<integrator type="direct"><integer name="shading_samples" value="4"/>
        </integrator>)");
    d = directOf(l);
    EXPECT_EQ(d.emitterSamples, 4);
    EXPECT_EQ(d.bsdfSamples, 4);
    l = load(R"(<integrator type="direct"><integer name="bsdf_samples" value="2"/>
        </integrator>)");
    d = directOf(l);
    EXPECT_EQ(d.emitterSamples, 1);
    EXPECT_EQ(d.bsdfSamples, 2);
}

TEST(Integrator, DirectErrors) {
    TempDir dir;
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        const std::string path = dir.write("d.xml", sceneXml(body));
        expectError(
            [&] {
                Loaded l{loadScene(path), {}};
                directOf(l);
            },
            "d.xml", line, reason);
    };
    bad("<integrator type=\"direct\">\n<integer name=\"emitter_samples\" value=\"-1\"/>"
        "</integrator>",
        4, "parameter 'emitter_samples' must be >= 0");
    bad("<integrator type=\"direct\">\n<integer name=\"bsdf_samples\" value=\"2\"/>\n"
        "<integer name=\"shading_samples\" value=\"2\"/></integrator>",
        5, "'shading_samples' cannot be combined with 'emitter_samples' or 'bsdf_samples'");
    bad("<integrator type=\"direct\">\n<integer name=\"shading_samples\" value=\"0\"/>"
        "</integrator>",
        3, "needs at least one emitter or BSDF sample");
    bad("<integrator type=\"direct\">\n<float name=\"bsdf_samples\" value=\"1.5\"/>"
        "</integrator>",
        4, "bsdf_samples");
}

TEST(Integrator, DirectWarnsAboutPathParameters) {
    Loaded l = load(
        "<integrator type=\"direct\">\n<integer name=\"max_depth\" value=\"3\"/>"
        "</integrator>");
    directOf(l);
    EXPECT_TRUE(hasWarning(l.warnings, {"scene.xml:4:", "'max_depth' of integrator 'direct' is not read"}));
}

// Unsupported Mitsuba integrators render with the nearest caustica integrator, with a warning
// naming file:line, the original and the replacement; the shared path parameters are read.
TEST(Integrator, UnknownTypesMapToPath) {
    for (const char* type : {"volpath", "volpathmis", "prb", "ptracer", "bdpt", "depth"}) {
        SCOPED_TRACE(type);
        Loaded l = load(std::string("<integrator type=\"") + type +
                        "\">\n<integer name=\"max_depth\" value=\"4\"/>\n"
                        "<boolean name=\"hide_emitters\" value=\"true\"/>"
                        "</integrator>");
        EXPECT_EQ(l.scene.integrator.type, "path");
        const PathSettings p = pathOf(l);
        EXPECT_EQ(p.maxDepth, 4);
        EXPECT_TRUE(p.hideEmitters);
        EXPECT_TRUE(hasWarning(l.warnings, {"scene.xml:3:", std::string("integrator '") + type + "'",
                                            "rendering with 'path' instead"}));
        EXPECT_EQ(l.warnings.size(), 1u);
    }
}

TEST(Integrator, UnknownTypeWarnsAboutItsOwnParameters) {
    Loaded l = load(
        "<integrator type=\"ptracer\">\n<integer name=\"samples_per_pass\" value=\"8\"/>"
        "</integrator>");
    EXPECT_EQ(l.scene.integrator.type, "path");
    EXPECT_EQ(pathOf(l).maxDepth, -1);
    EXPECT_TRUE(hasWarning(l.warnings, {"scene.xml:3:", "'ptracer'", "rendering with 'path'"}));
    EXPECT_TRUE(hasWarning(l.warnings, {"scene.xml:4:", "'samples_per_pass' of integrator 'path' is not read"}));
}

TEST(Integrator, DirectProjectiveMapsToDirect) {
    Loaded l = load(R"(<integrator type="direct_projective"/>)");
    EXPECT_EQ(l.scene.integrator.type, "direct");
    EXPECT_TRUE(hasWarning(
        l.warnings, {"scene.xml:3:", "'direct_projective'", "rendering with 'direct' instead"}));
}

// A wrapper caustica does not support (moment) renders with the integrator nested in it.
TEST(Integrator, WrapperMapsToNestedIntegrator) {
    Loaded l = load(
        "<integrator type=\"moment\">\n"
        "<integrator type=\"direct\" name=\"direct\">\n"
        "<integer name=\"emitter_samples\" value=\"2\"/></integrator></integrator>");
    EXPECT_EQ(l.scene.integrator.type, "direct");
    EXPECT_EQ(directOf(l).emitterSamples, 2);
    EXPECT_TRUE(hasWarning(l.warnings, {"scene.xml:3:", "integrator 'moment'",
                                        "nested integrator 'direct' (line 4) instead"}));
}

TEST(Integrator, PathSettingsAndErrors) {
    Loaded l = load(R"(<integrator type="path">
        <integer name="max_depth" value="8"/><integer name="rr_depth" value="3"/>
        <boolean name="hide_emitters" value="true"/></integrator>)");
    const PathSettings p = pathOf(l);
    EXPECT_EQ(p.maxDepth, 8);
    EXPECT_EQ(p.rrDepth, 3);
    EXPECT_TRUE(p.hideEmitters);
    TempDir dir;
    const std::string path = dir.write("p.xml", sceneXml("<integrator type=\"path\">\n<integer name=\"max_depth\" "
                                                         "value=\"-2\"/></integrator>"));
    expectError(
        [&] {
            Loaded bad{loadScene(path), {}};
            pathOf(bad);
        },
        "p.xml", 4, "must be -1 (unbounded) or >= 0");
}

// The command line's options set the same parameters as the scene, with the same checks, and
// take their place; an option of another integrator is a warning.
TEST(Integrator, MltCommandLineOverridesTheScene) {
    Loaded l = load(R"(<integrator type="mlt"><integer name="chains" value="32"/>
        <float name="p_large" value="0.2"/></integrator>)");
    auto mlt = [&](const std::vector<IntegratorParam>& commandLine) {
        return readSettings<MltSettings>(l, [](IntegratorParams& p) { return readMltSettings(p, 1024); }, commandLine);
    };
    MltSettings s = mlt({});
    EXPECT_EQ(s.chains, 32u);
    EXPECT_FLOAT_EQ(s.largeStepProbability, 0.2f);
    s = mlt({{"chains", IntegratorParam::Kind::Text, "64", "--mlt-chains"}});
    EXPECT_EQ(s.chains, 64u);
    EXPECT_FLOAT_EQ(s.largeStepProbability, 0.2f);
    EXPECT_THROW(
        {
            try {
                mlt({{"p_large", IntegratorParam::Kind::Text, "nan", "--mlt-large-step"}});
            } catch (const Error& e) {
                EXPECT_STREQ(e.what(), "--mlt-large-step nan: must be a finite number in [0, 1]");
                throw;
            }
        },
        Error);
    Loaded path = load(R"(<integrator type="path"/>)");
    readSettings<PathSettings>(path, readPathSettings, {{"chains", IntegratorParam::Kind::Text, "64", "--mlt-chains"}});
    EXPECT_TRUE(hasWarning(path.warnings, {"--mlt-chains is not an option of the path integrator; ignored"}));
}

// Settings no integrator can run are refused when the render is made, before any sample, with the
// scene file and line (io/ loads such a scene: it keeps the <integrator> as written).
TEST(Integrator, BadSettingsInASceneFileRefuseTheRender) {
    const std::string dir = CAUSTICA_SOURCE_DIR "/tests/render/data/";
    const struct {
        const char* file;
        int line;
        const char* reason;
    } cases[] = {{"direct_samples_conflict.xml", 5,
                  "'shading_samples' cannot be combined with 'emitter_samples' or 'bsdf_samples'"},
                 {"direct_no_samples.xml", 4, "integrator 'direct': needs at least one emitter or BSDF sample"}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file);
        Scene scene = loadScene(dir + c.file);
        RenderRequest request;
        request.device = "cpu";
        expectError([&] { Renderer renderer(std::move(scene), request); }, c.file, c.line, c.reason);
    }
}

// `caustica info` and --help name what will run: the registry describes each integrator's settings.
TEST(Integrator, RegistryDescribesEveryIntegrator) {
    const std::map<std::string, std::string> expected = {
        {"path", "max_depth -1, rr_depth 5"}, {"direct", "emitter_samples 1, bsdf_samples 1"}, {"mlt", "chains 1024"},
        {"sppm", "photon_count 131072"}, {"ppm", "hitpoints 1"}, {"whitted", "max_depth -1, rr_depth 5"}};
    ASSERT_EQ(integratorRegistry().size(), expected.size());
    for (const IntegratorEntry& e : integratorRegistry()) {
        SCOPED_TRACE(e.name);
        IntegratorSpec spec;
        spec.type = e.name;
        IntegratorParams params(spec);
        EXPECT_NE(e.describe(params).find(expected.at(e.name)), std::string::npos) << e.describe(params);
        EXPECT_EQ(&findIntegrator(e.name), &e);
    }
    EXPECT_THROW(findIntegrator("bdpt"), Error);
}

}  // namespace
}  // namespace caustica::test
