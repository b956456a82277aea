// integrator_test.cpp — the integrator plugins: direct's parameters (Mitsuba 3's direct.cpp
// defaults and errors) and the mapping of unsupported Mitsuba integrators to the nearest
// caustica one, with a warning naming file:line, the original and the replacement.
#include "scene_test_util.h"

namespace caustica::test {
namespace {

Scene withIntegrator(const std::string& integrator, std::vector<std::string>* warnings = nullptr) {
    TempDir dir;
    return loadXml(dir, sceneXml(integrator), warnings);
}

TEST(Integrator, DirectDefaults) {
    std::vector<std::string> warnings;
    const Scene s = withIntegrator(R"(<integrator type="direct"/>)", &warnings);
    EXPECT_EQ(s.integrator.type, IntegratorType::Direct);
    EXPECT_EQ(s.integrator.emitterSamples, 1);
    EXPECT_EQ(s.integrator.bsdfSamples, 1);
    EXPECT_FALSE(s.integrator.hideEmitters);
    EXPECT_TRUE(warnings.empty());
}

TEST(Integrator, DirectSampleCounts) {
    Scene s =
        withIntegrator(R"(<integrator type="direct"><integer name="emitter_samples" value="3"/>
        <integer name="bsdf_samples" value="0"/><boolean name="hide_emitters" value="true"/>
        </integrator>)");
    EXPECT_EQ(s.integrator.emitterSamples, 3);
    EXPECT_EQ(s.integrator.bsdfSamples, 0);
    EXPECT_TRUE(s.integrator.hideEmitters);
    // shading_samples sets both; a count not given takes shading_samples' value (default 1).
    s = withIntegrator(R"(<integrator type="direct"><integer name="shading_samples" value="4"/>
        </integrator>)");
    EXPECT_EQ(s.integrator.emitterSamples, 4);
    EXPECT_EQ(s.integrator.bsdfSamples, 4);
    s = withIntegrator(R"(<integrator type="direct"><integer name="bsdf_samples" value="2"/>
        </integrator>)");
    EXPECT_EQ(s.integrator.emitterSamples, 1);
    EXPECT_EQ(s.integrator.bsdfSamples, 2);
}

TEST(Integrator, DirectErrors) {
    TempDir dir;
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        const std::string path = dir.write("d.xml", sceneXml(body));
        expectError([&] { loadScene(path); }, "d.xml", line, reason);
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
    std::vector<std::string> warnings;
    withIntegrator(
        "<integrator type=\"direct\">\n<integer name=\"max_depth\" value=\"3\"/>"
        "</integrator>",
        &warnings);
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:4:", "'max_depth' is not used"}));
}

// Unsupported Mitsuba integrators render with the nearest caustica integrator, with a warning
// naming file:line, the original and the replacement; the shared path parameters are read.
TEST(Integrator, UnknownTypesMapToPath) {
    for (const char* type : {"volpath", "volpathmis", "prb", "ptracer", "bdpt", "sppm", "depth"}) {
        SCOPED_TRACE(type);
        std::vector<std::string> warnings;
        const Scene s = withIntegrator(std::string("<integrator type=\"") + type +
                                           "\">\n<integer name=\"max_depth\" value=\"4\"/>\n"
                                           "<boolean name=\"hide_emitters\" value=\"true\"/>"
                                           "</integrator>",
                                       &warnings);
        EXPECT_EQ(s.integrator.type, IntegratorType::Path);
        EXPECT_EQ(s.integrator.maxDepth, 4);
        EXPECT_TRUE(s.integrator.hideEmitters);
        EXPECT_TRUE(hasWarning(warnings, {"scene.xml:3:", std::string("integrator '") + type + "'",
                                          "rendering with 'path' instead"}));
        EXPECT_EQ(warnings.size(), 1u);
    }
}

TEST(Integrator, UnknownTypeWarnsAboutItsOwnParameters) {
    std::vector<std::string> warnings;
    const Scene s = withIntegrator(
        "<integrator type=\"ptracer\">\n<integer name=\"samples_per_pass\" value=\"8\"/>"
        "</integrator>",
        &warnings);
    EXPECT_EQ(s.integrator.type, IntegratorType::Path);
    EXPECT_EQ(s.integrator.maxDepth, -1);
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:3:", "'ptracer'", "rendering with 'path'"}));
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:4:", "'samples_per_pass' is not used"}));
}

TEST(Integrator, DirectProjectiveMapsToDirect) {
    std::vector<std::string> warnings;
    const Scene s = withIntegrator(R"(<integrator type="direct_projective"/>)", &warnings);
    EXPECT_EQ(s.integrator.type, IntegratorType::Direct);
    EXPECT_TRUE(hasWarning(
        warnings, {"scene.xml:3:", "'direct_projective'", "rendering with 'direct' instead"}));
}

// A wrapper (aov) renders with the integrator nested in it.
TEST(Integrator, WrapperMapsToNestedIntegrator) {
    std::vector<std::string> warnings;
    const Scene s = withIntegrator(
        "<integrator type=\"aov\">\n<string name=\"aovs\" value=\"dd.y:depth\"/>\n"
        "<integrator type=\"direct\" name=\"direct\">\n"
        "<integer name=\"emitter_samples\" value=\"2\"/></integrator></integrator>",
        &warnings);
    EXPECT_EQ(s.integrator.type, IntegratorType::Direct);
    EXPECT_EQ(s.integrator.emitterSamples, 2);
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:3:", "integrator 'aov'",
                                      "nested integrator 'direct' (line 5) instead"}));
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:4:", "'aovs' is not used"}));
}

}  // namespace
}  // namespace caustica::test
