// bsdf_emitter_test.cpp — BSDF and emitter plugins: defaults as in Mitsuba 3, named IORs,
// twosided children, area/point/constant emitters and the refusals of what is not supported.
#include "scene_test_util.h"

namespace caustica::test {
namespace {

/// Loads one rectangle carrying `bsdf` and returns the BSDF record the shape points to.
Bsdf shapeBsdf(const std::string& bsdf, Scene* out = nullptr) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml("<shape type=\"rectangle\">" + bsdf + "</shape>"));
    Bsdf b = s.bsdfs.at(s.shapes.at(0).bsdf);
    if (out) *out = s;
    return b;
}

TEST(Bsdf, DiffuseAndTheDefault) {
    Bsdf def = shapeBsdf("");
    EXPECT_EQ(def.type, BsdfType::Diffuse);
    EXPECT_EQ(def.reflectance.g, 0.5f);
    Bsdf d =
        shapeBsdf(R"(<bsdf type="diffuse"><rgb name="reflectance" value="0.1, 0.2, 0.3"/></bsdf>)");
    EXPECT_EQ(d.reflectance.b, 0.3f);
    Bsdf f = shapeBsdf(R"(<bsdf type="diffuse"><float name="reflectance" value="0.75"/></bsdf>)");
    EXPECT_EQ(f.reflectance.r, 0.75f);
}

TEST(Bsdf, DielectricIors) {
    Bsdf def = shapeBsdf(R"(<bsdf type="dielectric"/>)");
    EXPECT_EQ(def.type, BsdfType::Dielectric);
    EXPECT_FLOAT_EQ(def.etaRatio, 1.5046f / 1.000277f);
    EXPECT_EQ(def.reflectance.r, 1.0f);
    EXPECT_EQ(def.transmittance.r, 1.0f);
    Bsdf named = shapeBsdf(R"(<bsdf type="dielectric"><string name="int_ior" value="water"/>
        <string name="ext_ior" value="Vacuum"/></bsdf>)");
    EXPECT_FLOAT_EQ(named.etaRatio, 1.3330f);
    Bsdf diamond = shapeBsdf(R"(<bsdf type="dielectric"><string name="int_ior" value="diamond"/>
        <string name="ext_ior" value="water ice"/>
        <rgb name="specular_transmittance" value="0.5"/></bsdf>)");
    EXPECT_FLOAT_EQ(diamond.etaRatio, 2.419f / 1.31f);
    EXPECT_EQ(diamond.transmittance.g, 0.5f);
    Bsdf num = shapeBsdf(R"(<bsdf type="dielectric"><float name="int_ior" value="1.2"/>
        <float name="ext_ior" value="1.1"/></bsdf>)");
    EXPECT_FLOAT_EQ(num.etaRatio, 1.2f / 1.1f);
}

TEST(Bsdf, Conductors) {
    Bsdf mirror = shapeBsdf(R"(<bsdf type="conductor"/>)");
    EXPECT_EQ(mirror.type, BsdfType::Conductor);
    EXPECT_EQ(mirror.eta.r, 0.0f);
    EXPECT_EQ(mirror.k.r, 1.0f);
    EXPECT_EQ(mirror.reflectance.r, 1.0f);
    Bsdf metal = shapeBsdf(R"(<bsdf type="conductor"><rgb name="eta" value="0.2, 0.9, 1.1"/>
        <rgb name="k" value="3.9, 2.4, 2.2"/><string name="material" value="none"/></bsdf>)");
    EXPECT_EQ(metal.eta.g, 0.9f);
    EXPECT_EQ(metal.k.b, 2.2f);
    Bsdf rough = shapeBsdf(R"(<bsdf type="roughconductor">
        <string name="distribution" value="ggx"/><float name="alpha" value="0.3"/></bsdf>)");
    EXPECT_EQ(rough.type, BsdfType::RoughConductor);
    EXPECT_EQ(rough.alphaU, 0.3f);
    EXPECT_EQ(rough.alphaV, 0.3f);
    Bsdf aniso = shapeBsdf(R"(<bsdf type="roughconductor"><string name="distribution" value="GGX"/>
        <float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/>
        <boolean name="sample_visible" value="false"/></bsdf>)");
    EXPECT_EQ(aniso.alphaU, 0.05f);
    EXPECT_EQ(aniso.alphaV, 0.4f);
    Bsdf defAlpha = shapeBsdf(R"(<bsdf type="roughconductor">
        <string name="distribution" value="ggx"/></bsdf>)");
    EXPECT_EQ(defAlpha.alphaU, 0.1f);
}

TEST(Bsdf, TwoSidedChildren) {
    Scene s;
    Bsdf one = shapeBsdf(R"(<bsdf type="twosided"><bsdf type="conductor"/></bsdf>)", &s);
    EXPECT_EQ(one.type, BsdfType::TwoSided);
    EXPECT_EQ(one.front, one.back);
    EXPECT_EQ(s.bsdfs[one.front].type, BsdfType::Conductor);
    TempDir dir;
    Scene two = loadXml(dir, sceneXml(R"(
        <bsdf type="diffuse" id="back"><rgb name="reflectance" value="0.9"/></bsdf>
        <shape type="rectangle"><bsdf type="twosided">
            <bsdf type="roughconductor"><string name="distribution" value="ggx"/></bsdf>
            <ref id="back"/>
        </bsdf></shape>)"));
    const Bsdf& t = two.bsdfs[two.shapes[0].bsdf];
    EXPECT_EQ(two.bsdfs[t.front].type, BsdfType::RoughConductor);
    EXPECT_EQ(two.bsdfs[t.back].reflectance.r, 0.9f);
}

TEST(Bsdf, Refusals) {
    TempDir dir;
    auto bad = [&](const std::string& bsdf, int line, const std::string& reason) {
        std::string path =
            dir.write("b.xml", sceneXml("<shape type=\"rectangle\">\n" + bsdf + "\n</shape>"));
        expectError([&] { loadScene(path); }, "b.xml", line, reason);
    };
    bad("<bsdf type=\"roughconductor\"/>", 4, "add <string name=\"distribution\" value=\"ggx\"/>");
    bad("<bsdf type=\"roughconductor\">\n<string name=\"distribution\" value=\"beckmann\"/></bsdf>",
        5, "'beckmann' is not supported yet; use value=\"ggx\"");
    bad("<bsdf type=\"roughconductor\">\n<string name=\"distribution\" value=\"ggx\"/>\n"
        "<float name=\"alpha\" value=\"0.1\"/><float name=\"alpha_u\" value=\"0.1\"/></bsdf>",
        4, "either 'alpha' or 'alpha_u'");
    bad("<bsdf type=\"conductor\">\n<string name=\"material\" value=\"Au\"/></bsdf>", 5,
        "measured conductor data ('Au'), which is not supported yet");
    bad("<bsdf type=\"dielectric\">\n<string name=\"int_ior\" value=\"glass\"/></bsdf>", 5,
        "unknown material 'glass'");
    bad("<bsdf type=\"dielectric\">\n<float name=\"int_ior\" value=\"-1\"/></bsdf>", 5,
        "'int_ior' must be positive");
    bad("<bsdf type=\"twosided\"/>", 4, "needs one or two nested bsdfs, got 0");
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"dielectric\"/></bsdf>", 5,
        "cannot wrap a transmissive bsdf");
    bad("<bsdf type=\"plastic\"/>", 4,
        "unsupported bsdf type 'plastic' (supported: conductor, "
        "dielectric, diffuse, roughconductor, twosided)");
    bad("<bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"-0.5\"/></bsdf>", 5,
        "must be finite and non-negative");
    bad("<bsdf type=\"diffuse\">\n<string name=\"reflectance\" value=\"red\"/></bsdf>", 5,
        "must be an <rgb>, <spectrum> or <float>, not <string>");
    bad("<bsdf type=\"diffuse\">\n<bsdf type=\"diffuse\"/></bsdf>", 5,
        "bsdf 'diffuse' cannot contain a <bsdf>");
    bad("<bsdf type=\"diffuse\"/>\n<bsdf type=\"diffuse\"/>", 5, "at most one bsdf");
}

TEST(Emitter, AreaPointConstant) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(
        <emitter type="point"><rgb name="intensity" value="5"/>
            <point name="position" value="0, 3, 0"/></emitter>
        <shape type="sphere"><float name="radius" value="0.5"/>
            <emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>
        <emitter type="point"><transform name="to_world"><translate x="7"/></transform></emitter>
        <emitter type="constant"><rgb name="radiance" value="0.25"/></emitter>
        <shape type="rectangle" id="lamp"><ref id="lamp_light"/></shape>
        <emitter type="area" id="lamp_light"/>)"));
    ASSERT_EQ(s.lights.size(), 5u);
    EXPECT_EQ(s.lights[0].type, LightType::Point);
    EXPECT_EQ(s.lights[0].radiance.r, 5.0f);
    EXPECT_EQ(s.lights[0].position, Vec3f(0, 3, 0));
    EXPECT_EQ(s.lights[1].type, LightType::Area);
    EXPECT_EQ(s.lights[1].radiance.b, 3.0f);
    EXPECT_EQ(s.lights[1].shape, 0u);
    EXPECT_EQ(s.shapes[0].light, 1);
    EXPECT_EQ(s.lights[2].position, Vec3f(7, 0, 0));
    EXPECT_EQ(s.lights[2].radiance.r, 1.0f);
    EXPECT_EQ(s.lights[3].type, LightType::Constant);
    EXPECT_EQ(s.environmentLight, 3);
    EXPECT_EQ(s.lights[4].type, LightType::Area);
    EXPECT_EQ(s.lights[4].radiance.r, 1.0f);  // Mitsuba's default radiance
    EXPECT_EQ(s.shapes[1].light, 4);
    EXPECT_EQ(s.lights[4].shape, 1u);
    EXPECT_NEAR(s.lights[4].area, 4.0f, 1e-5f);
}

TEST(Emitter, Refusals) {
    TempDir dir;
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        std::string path = dir.write("e.xml", sceneXml(body));
        expectError([&] { loadScene(path); }, "e.xml", line, reason);
    };
    bad("<emitter type=\"area\"/>", 3, "area emitter must be nested in (or referenced by) a shape");
    bad("<shape type=\"cube\">\n<emitter type=\"point\"/></shape>", 4,
        "only area emitters can be attached to a shape");
    bad("<emitter type=\"point\"><point name=\"position\" value=\"0 0 0\"/>\n"
        "<transform name=\"to_world\"/></emitter>",
        3, "either 'position' or 'to_world'");
    bad("<emitter type=\"constant\"/>\n<emitter type=\"constant\"/>", 4,
        "only one environment emitter");
    bad("<emitter type=\"envmap\"/>", 3, "unsupported emitter type 'envmap'");
    bad("<shape type=\"cube\">\n<emitter type=\"area\">\n<spectrum name=\"radiance\" "
        "value=\"400:1, 700:2\"/></emitter></shape>",
        5, "wavelength:value pairs is not supported yet");
    bad("<emitter type=\"area\" id=\"l\"/>\n<shape type=\"cube\"><ref id=\"l\"/></shape>\n"
        "<shape type=\"cube\"><ref id=\"l\"/></shape>",
        5, "is already attached to a shape");
}

}  // namespace
}  // namespace caustica::test
