// xml_parser_test.cpp — Mitsuba XML structure: properties, <default> and $name, -D overrides,
// <include>, ids and <ref>, the pre-2.0 upgrade, and warnings for parameters never read.
#include "scene_test_util.h"

namespace caustica::test {
namespace {

TEST(XmlParser, PropertyTypesAreParsed) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(
        <emitter type="point">
            <point name="position" value="1, 2.5, -3"/>
            <rgb name="intensity" value="0.5"/>
        </emitter>
        <emitter type="point">
            <point name="position" x="4" y="5" z="6"/>
            <spectrum name="intensity" value="2"/>
        </emitter>
        <integrator type="path">
            <integer name="max_depth" value="+7"/>
            <boolean name="hide_emitters" value="True"/>
        </integrator>)"));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].position, Vec3f(1, 2.5f, -3));
    EXPECT_EQ(s.lights[0].radiance.g, 0.5f);
    EXPECT_EQ(s.lights[1].position, Vec3f(4, 5, 6));
    // A single-value spectrum in an emitter is equal-energy white: 2 * xyz_to_srgb(1, 1, 1).
    EXPECT_NEAR(s.lights[1].radiance.b, 1.81783f, 1e-4f);
    EXPECT_EQ(integratorParam(s, "max_depth"), "7");
    EXPECT_EQ(integratorParam(s, "hide_emitters"), "true");
}

TEST(XmlParser, DefaultsAndDefinesSubstituteAnyAttribute) {
    TempDir dir;
    const std::string xml = sceneXml(R"(
        <default name="spp" value="16"/>
        <default name="integrator" value="path"/>
        <default name="depth" value="3"/>
        <integrator type="$integrator">
            <integer name="max_depth" value="$depth"/>
            <integer name="rr_depth" value="1$depth"/>
        </integrator>)",
                                     false);
    const std::string sensor = R"(<sensor type="perspective"><sampler type="independent">
            <integer name="sample_count" value="$spp"/></sampler></sensor>)";
    std::string full = xml;
    full.insert(full.find("</scene>"), sensor);
    Scene a = loadXml(dir, full);
    EXPECT_EQ(a.sampleCount, 16);
    EXPECT_EQ(integratorParam(a, "max_depth"), "3");
    EXPECT_EQ(integratorParam(a, "rr_depth"), "13");
    Scene b = loadXml(dir, full, nullptr, {{"spp", "64"}, {"depth", "5"}});
    EXPECT_EQ(b.sampleCount, 64);
    EXPECT_EQ(integratorParam(b, "max_depth"), "5");
    EXPECT_EQ(integratorParam(b, "rr_depth"), "15");
}

TEST(XmlParser, UndefinedParameterIsAnError) {
    TempDir dir;
    std::string path = dir.write("scene.xml", sceneXml(R"(<integrator type="path">
        <integer name="max_depth" value="$depth"/></integrator>)"));
    expectError([&] { loadScene(path); }, "scene.xml", 4, "undefined parameter '$depth'");
}

TEST(XmlParser, UnusedDefineIsAWarning) {
    TempDir dir;
    std::vector<std::string> warnings;
    loadXml(dir, sceneXml(""), &warnings, {{"spp", "4"}});
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml", "define 'spp' is never used"}));
}

TEST(XmlParser, IncludeIsRelativeToTheIncludingFile) {
    TempDir dir;
    dir.write("parts/materials.xml", R"(<scene version="3.0.0">
        <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
        <include filename="more/light.xml"/>
    </scene>)");
    dir.write("parts/more/light.xml", R"(<emitter type="constant"/>)");
    Scene s = loadXml(dir, sceneXml(R"(
        <include filename="parts/materials.xml"/>
        <shape type="rectangle"><ref id="red"/></shape>)"));
    ASSERT_EQ(s.bsdfs.size(), 1u);
    EXPECT_EQ(s.bsdfs[0].reflectance.r, 0.8f);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Constant);
    EXPECT_EQ(s.environmentLight, 0);
}

TEST(XmlParser, IncludeCycleIsDetected) {
    TempDir dir;
    dir.write("a.xml", "<scene version=\"3.0.0\">\n<include filename=\"b.xml\"/>\n</scene>\n");
    dir.write("b.xml", "<scene version=\"3.0.0\">\n\n<include filename=\"a.xml\"/>\n</scene>\n");
    std::string path = dir.write("scene.xml", sceneXml("<include filename=\"a.xml\"/>"));
    expectError([&] { loadScene(path); }, "b.xml", 3, "include cycle: a.xml -> b.xml -> a.xml");
    // Through a subfolder, and a file including itself.
    auto including = [](const std::string& file) {
        return "<scene version=\"3.0.0\">\n<include filename=\"" + file + "\"/>\n</scene>\n";
    };
    dir.write("parts/c.xml", including("../d.xml"));
    dir.write("d.xml", including("parts/c.xml"));
    dir.write("self.xml", including("self.xml"));
    expectError([&] { loadScene(dir.path("d.xml")); }, "c.xml", 2,
                "include cycle: d.xml -> parts/c.xml -> d.xml");
    expectError([&] { loadScene(dir.path("self.xml")); }, "self.xml", 2,
                "include cycle: self.xml -> self.xml");
}

TEST(XmlParser, ReferencesShareOneRecordAndMayPointToNestedObjects) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(
        <shape type="rectangle">
            <bsdf type="diffuse" id="inner"><rgb name="reflectance" value="0.25"/></bsdf>
        </shape>
        <shape type="cube"><ref name="bsdf" id="inner"/></shape>
        <shape type="disk"><ref id="later"/></shape>
        <bsdf type="conductor" id="later"/>)"));
    ASSERT_EQ(s.shapes.size(), 3u);
    EXPECT_EQ(s.shapes[0].bsdf, s.shapes[1].bsdf);
    EXPECT_EQ(s.bsdfs.size(), 2u);
    EXPECT_EQ(s.bsdfs[s.shapes[2].bsdf].type, BsdfType::Conductor);
}

TEST(XmlParser, UnknownAndDuplicateIdsAreErrors) {
    TempDir dir;
    std::string a =
        dir.write("a.xml", sceneXml("<shape type=\"cube\">\n<ref id=\"nope\"/>\n</shape>"));
    expectError([&] { loadScene(a); }, "a.xml", 4, "<ref id=\"nope\">: no object has this id");
    std::string b = dir.write("b.xml", sceneXml("<bsdf type=\"diffuse\" id=\"x\"/>\n"
                                                "<bsdf type=\"diffuse\" id=\"x\"/>"));
    expectError([&] { loadScene(b); }, "b.xml", 4, "duplicate id 'x' (first used at");
}

TEST(XmlParser, UnreadParametersAreWarningsWithFileAndLine) {
    TempDir dir;
    std::vector<std::string> warnings;
    Scene s = loadXml(dir, sceneXml(R"(<shape type="rectangle">
        <bsdf type="diffuse">
            <rgb name="reflectanse" value="0.1"/>
        </bsdf>
    </shape>)"),
                      &warnings);
    EXPECT_EQ(s.bsdfs[0].reflectance.r, 0.5f);  // the misspelt value was not used
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:5:", "'reflectanse'", "not used"}));
}

TEST(XmlParser, UnusedNamedObjectIsAWarning) {
    TempDir dir;
    std::vector<std::string> warnings;
    loadXml(dir, sceneXml("<bsdf type=\"diffuse\" id=\"spare\"/>"), &warnings);
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:3:", "(id 'spare') is declared but never used"}));
}

TEST(XmlParser, WarningsGoToStderrWithoutASink) {
    TempDir dir;
    std::string path = dir.write("scene.xml", sceneXml("<bsdf type=\"diffuse\" id=\"spare\"/>"));
    testing::internal::CaptureStderr();
    loadScene(path);
    std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("warning: "), std::string::npos);
    EXPECT_NE(err.find("never used"), std::string::npos);
}

TEST(XmlParser, LegacyVersionIsUpgradedLikeMitsuba) {
    TempDir dir;
    Scene s = loadXml(dir, R"(<scene version="0.6.0">
        <sensor type="perspective">
            <float name="fov" value="30"/>
            <string name="fovAxis" value="y"/>
            <transform name="toWorld">
                <lookAt origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
            <sampler type="independent"><integer name="sampleCount" value="9"/></sampler>
        </sensor>
        <shape type="rectangle">
            <bsdf type="dielectric"><float name="intIOR" value="1.33"/></bsdf></shape>
    </scene>)");
    EXPECT_EQ(s.sampleCount, 9);
    EXPECT_NEAR(s.camera.tanHalfY, std::tan(0.5 * 30 * M_PI / 180), 1e-6);
    EXPECT_NEAR(s.camera.worldFromCamera.m.m[2][3], 5.0f, 1e-6f);
    EXPECT_NEAR(s.bsdfs[0].etaRatio, 1.33f / 1.000277f, 1e-6f);
}

}  // namespace
}  // namespace caustica::test
