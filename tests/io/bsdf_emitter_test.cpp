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

// Mitsuba 3 gives a shape with an area emitter and no BSDF a black diffuse BSDF (its Shape
// constructor), not the 0.5 grey of other shapes.
TEST(Bsdf, EmitterShapeDefaultIsBlack) {
    TempDir dir;
    const Scene s = loadScene(dir.write("e.xml", sceneXml(R"(
        <shape type="rectangle"><emitter type="area"/></shape>
        <shape type="rectangle"/>
        <shape type="rectangle"><emitter type="area"/></shape>)")));
    ASSERT_EQ(s.shapes.size(), 3u);
    EXPECT_EQ(s.bsdfs[s.shapes[0].bsdf].type, BsdfType::Diffuse);
    EXPECT_EQ(s.bsdfs[s.shapes[0].bsdf].reflectance.g, 0.0f);
    EXPECT_EQ(s.bsdfs[s.shapes[1].bsdf].reflectance.g, 0.5f);
    EXPECT_EQ(s.shapes[0].bsdf, s.shapes[2].bsdf);  // one shared record
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

// Mitsuba 3's defaults: Beckmann roughness, named conductors as Mitsuba's own RGB eta/k.
TEST(Bsdf, BeckmannDefaultAndNamedConductors) {
    Bsdf beck = shapeBsdf(R"(<bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf>)");
    EXPECT_EQ(beck.distribution, MicrofacetType::Beckmann);
    EXPECT_EQ(beck.alphaU, 0.2f);
    Bsdf ggx = shapeBsdf(R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/></bsdf>)");
    EXPECT_EQ(ggx.distribution, MicrofacetType::GGX);
    Bsdf au = shapeBsdf(R"(<bsdf type="conductor"><string name="material" value="Au"/></bsdf>)");
    EXPECT_NEAR(au.eta.r, 0.143036f, 1e-5f);  // mi.traverse of Mitsuba 3.9.1's conductor 'Au'
    EXPECT_NEAR(au.eta.b, 1.44205f, 1e-5f);
    EXPECT_NEAR(au.k.g, 2.38556f, 1e-5f);
    Bsdf cu = shapeBsdf(R"(<bsdf type="roughconductor"><string name="material" value="Cu"/></bsdf>)");
    EXPECT_GT(cu.k.r, 3.0f);
    for (const char* m : {"a-C", "Ag", "Al", "AlAs", "AlSb", "Be", "Cr", "CsI", "Cu2O", "CuO", "d-C",
                          "Hg", "HgTe", "Ir", "K", "Li", "MgO", "Mo", "Na_palik", "Nb", "Ni_palik",
                          "Rh", "Se", "SiC", "SnTe", "Ta", "Te", "ThF4", "TiC", "TiN", "TiO2", "VC",
                          "V_palik", "VN", "W"}) {
        Bsdf b = shapeBsdf(std::string("<bsdf type=\"conductor\"><string name=\"material\" value=\"") +
                           m + "\"/></bsdf>");
        // (Mitsuba clamps out-of-gamut RGB to zero: AlSb's red eta and k are both 0.)
        EXPECT_GT(b.eta.r + b.eta.g + b.eta.b + b.k.r + b.k.g + b.k.b, 0.0f) << m;
    }
}

TEST(Bsdf, ThinDielectric) {
    Bsdf def = shapeBsdf(R"(<bsdf type="thindielectric"/>)");
    EXPECT_EQ(def.type, BsdfType::ThinDielectric);
    EXPECT_NEAR(def.etaRatio, 1.5046f / 1.000277f, 1e-6f);
    Bsdf t = shapeBsdf(R"(<bsdf type="thindielectric"><string name="int_ior" value="water"/>
        <float name="ext_ior" value="1"/><rgb name="specular_transmittance" value="0.5, 0.6, 0.7"/>
        <float name="specular_reflectance" value="0.8"/></bsdf>)");
    EXPECT_NEAR(t.etaRatio, 1.333f, 1e-6f);
    EXPECT_EQ(t.transmittance.b, 0.7f);
    EXPECT_EQ(t.reflectance.r, 0.8f);
}

TEST(Bsdf, RoughDielectric) {
    Bsdf def = shapeBsdf(R"(<bsdf type="roughdielectric"/>)");
    EXPECT_EQ(def.type, BsdfType::RoughDielectric);
    EXPECT_EQ(def.distribution, MicrofacetType::Beckmann);
    EXPECT_EQ(def.alphaU, 0.1f);
    EXPECT_NEAR(def.etaRatio, 1.5046f / 1.000277f, 1e-6f);
    Bsdf g = shapeBsdf(R"(<bsdf type="roughdielectric"><string name="distribution" value="ggx"/>
        <float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.3"/>
        <string name="int_ior" value="water"/><float name="specular_transmittance" value="0.5"/></bsdf>)");
    EXPECT_EQ(g.distribution, MicrofacetType::GGX);
    EXPECT_EQ(g.alphaV, 0.3f);
    EXPECT_NEAR(g.etaRatio, 1.333f / 1.000277f, 1e-6f);
    EXPECT_EQ(g.transmittance.g, 0.5f);
}

TEST(Bsdf, Plastic) {
    Bsdf def = shapeBsdf(R"(<bsdf type="plastic"/>)");
    EXPECT_EQ(def.type, BsdfType::Plastic);
    EXPECT_NEAR(def.etaRatio, 1.49f / 1.000277f, 1e-6f);  // polypropylene / air
    EXPECT_EQ(def.diffuse.g, 0.5f);
    EXPECT_EQ(def.reflectance.g, 1.0f);
    EXPECT_FALSE(def.nonlinear);
    EXPECT_NEAR(def.specularWeight, 1 / 1.5f, 1e-6f);
    Bsdf p = shapeBsdf(R"(<bsdf type="plastic"><float name="int_ior" value="1.9"/>
        <string name="ext_ior" value="water"/><rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/>
        <float name="specular_reflectance" value="0.5"/><boolean name="nonlinear" value="true"/></bsdf>)");
    EXPECT_NEAR(p.etaRatio, 1.9f / 1.333f, 1e-6f);
    EXPECT_EQ(p.diffuse.b, 0.3f);
    EXPECT_EQ(p.reflectance.r, 0.5f);
    EXPECT_TRUE(p.nonlinear);
    EXPECT_NEAR(p.specularWeight, 0.5f / 0.7f, 1e-6f);
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
    bad("<bsdf type=\"roughconductor\">\n<string name=\"distribution\" value=\"phong\"/></bsdf>",
        5, "must be 'beckmann' or 'ggx', not 'phong'");
    bad("<bsdf type=\"roughconductor\">\n<string name=\"distribution\" value=\"ggx\"/>\n"
        "<float name=\"alpha\" value=\"0.1\"/><float name=\"alpha_u\" value=\"0.1\"/></bsdf>",
        4, "either 'alpha' or 'alpha_u'");
    bad("<bsdf type=\"conductor\">\n<string name=\"material\" value=\"au\"/></bsdf>", 5,
        "names an unknown conductor 'au' (known: a-C, Ag, Al,");
    bad("<bsdf type=\"conductor\">\n<string name=\"material\" value=\"Au\"/>"
        "<float name=\"eta\" value=\"1\"/></bsdf>", 5, "cannot be combined with 'eta'/'k'");
    bad("<bsdf type=\"dielectric\">\n<string name=\"int_ior\" value=\"glass\"/></bsdf>", 5,
        "unknown material 'glass'");
    bad("<bsdf type=\"dielectric\">\n<float name=\"int_ior\" value=\"-1\"/></bsdf>", 5,
        "'int_ior' must be positive");
    bad("<bsdf type=\"twosided\"/>", 4, "needs one or two nested bsdfs, got 0");
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"dielectric\"/></bsdf>", 5,
        "cannot wrap a transmissive bsdf");
    bad("<bsdf type=\"hair\"/>", 4, "unsupported bsdf type 'hair' (supported: ");
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"roughdielectric\"/></bsdf>", 5,
        "cannot wrap a transmissive bsdf (roughdielectric)");
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"thindielectric\"/></bsdf>", 5,
        "cannot wrap a transmissive bsdf (thindielectric)");
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
    bad("<emitter type=\"envmap\"/>", 3, "missing required parameter 'filename'");
    bad("<emitter type=\"projector\"/>", 3, "unsupported emitter type 'projector'");
    bad("<shape type=\"cube\">\n<emitter type=\"area\">\n<spectrum name=\"radiance\" "
        "value=\"700:1, 400:2\"/></emitter></shape>",
        5, "wavelengths must increase");
    bad("<emitter type=\"area\" id=\"l\"/>\n<shape type=\"cube\"><ref id=\"l\"/></shape>\n"
        "<shape type=\"cube\"><ref id=\"l\"/></shape>",
        5, "is already attached to a shape");
}

}  // namespace
}  // namespace caustica::test
