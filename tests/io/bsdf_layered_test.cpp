// bsdf_layered_test.cpp — loading roughplastic, blendbsdf, mask and null: Mitsuba 3's parameters
// and defaults, nested and referenced children, and the refusals (Mitsuba's own and the bounds of
// caustica's kernels).
#include "caustica/scene/bsdf.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

/// Loads one rectangle carrying `bsdf`; returns the scene and the shape's BSDF index.
uint32_t shapeBsdf(const std::string& bsdf, Scene& s,
                   std::vector<std::string>* warnings = nullptr) {
    TempDir dir;
    s = loadXml(dir, sceneXml("<shape type=\"rectangle\">" + bsdf + "</shape>"), warnings);
    return s.shapes.at(0).bsdf;
}

TEST(LayeredBsdf, RoughPlasticDefaults) {
    Scene s;
    const Bsdf& b = s.bsdfs[shapeBsdf(R"(<bsdf type="roughplastic"/>)", s)];
    EXPECT_EQ(b.type, BsdfType::RoughPlastic);
    EXPECT_EQ(b.distribution, MicrofacetType::Beckmann);
    EXPECT_EQ(b.alphaU, 0.1f);
    EXPECT_EQ(b.alphaV, 0.1f);
    EXPECT_NEAR(b.etaRatio, 1.49f / 1.000277f, 1e-6f);  // polypropylene / air
    EXPECT_EQ(b.diffuse.g, 0.5f);
    EXPECT_EQ(b.reflectance.g, 1.0f);
    EXPECT_FALSE(b.nonlinear);
    EXPECT_NEAR(b.specularWeight, 1 / 1.5f, 1e-6f);
    // The table: transmittance into the coating, ~1 - F0 at normal incidence, falling towards
    // grazing (where visible normals still face the viewer: 0.37 at cosθ = 1e-6).
    EXPECT_NEAR(b.roughTransmittance[kRoughPlasticTableSize - 1], 0.96f, 0.01f);
    EXPECT_LT(b.roughTransmittance[0], b.roughTransmittance[kRoughPlasticTableSize / 4]);
    EXPECT_LT(b.roughTransmittance[kRoughPlasticTableSize / 4],
              b.roughTransmittance[kRoughPlasticTableSize - 1]);
    EXPECT_GT(b.fdrInt, 0.4f);  // internal reflectance of the coating (η 1.49: ~0.6)
    EXPECT_LT(b.fdrInt, 0.8f);
}

TEST(LayeredBsdf, RoughPlasticParameters) {
    Scene s;
    const Bsdf& b = s.bsdfs[shapeBsdf(R"(<bsdf type="roughplastic">
        <string name="distribution" value="GGX"/><float name="alpha" value="0.3"/>
        <float name="int_ior" value="1.6"/><string name="ext_ior" value="water"/>
        <rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/>
        <float name="specular_reflectance" value="0.5"/><boolean name="nonlinear" value="true"/>
        <boolean name="sample_visible" value="false"/></bsdf>)", s)];
    EXPECT_EQ(b.distribution, MicrofacetType::GGX);
    EXPECT_EQ(b.alphaU, 0.3f);
    EXPECT_NEAR(b.etaRatio, 1.6f / 1.333f, 1e-6f);
    EXPECT_EQ(b.diffuse.b, 0.3f);
    EXPECT_EQ(b.reflectance.r, 0.5f);
    EXPECT_TRUE(b.nonlinear);
    EXPECT_NEAR(b.specularWeight, 0.5f / 0.7f, 1e-6f);
}

TEST(LayeredBsdf, BlendMaskNull) {
    Scene s;
    TempDir dir;
    s = loadXml(dir, sceneXml(R"(
        <bsdf type="conductor" id="metal"/>
        <shape type="rectangle"><bsdf type="blendbsdf">
            <float name="weight" value="0.25"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.9"/></bsdf>
            <ref id="metal"/>
        </bsdf></shape>
        <shape type="rectangle"><bsdf type="mask">
            <rgb name="opacity" value="0.2, 0.5, 0.8"/>
            <bsdf type="twosided"><bsdf type="diffuse"/></bsdf>
        </bsdf></shape>
        <shape type="rectangle"><bsdf type="mask"><ref id="metal"/></bsdf></shape>
        <shape type="rectangle"><bsdf type="null"/></shape>
        <shape type="rectangle"><bsdf type="blendbsdf"><float name="weight" value="1.7"/>
            <bsdf type="diffuse"/><bsdf type="null"/></bsdf></shape>)"));
    const Bsdf& blend = s.bsdfs[s.shapes[0].bsdf];
    EXPECT_EQ(blend.type, BsdfType::Blend);
    EXPECT_EQ(blend.weight, 0.25f);
    EXPECT_EQ(s.bsdfs[blend.front].reflectance.r, 0.9f);  // bsdf_0: the first child
    EXPECT_EQ(s.bsdfs[blend.back].type, BsdfType::Conductor);
    const Bsdf& mask = s.bsdfs[s.shapes[1].bsdf];
    EXPECT_EQ(mask.type, BsdfType::Mask);
    EXPECT_NEAR(mask.weight, 0.5f, 1e-6f);  // an <rgb> opacity: its mean, as Mitsuba 3.9.1
    EXPECT_EQ(s.bsdfs[mask.front].type, BsdfType::TwoSided);
    const Bsdf& maskDefault = s.bsdfs[s.shapes[2].bsdf];
    EXPECT_EQ(maskDefault.weight, 0.5f);  // Mitsuba's default opacity
    EXPECT_EQ(maskDefault.front, blend.back);  // the referenced conductor is one record
    EXPECT_EQ(s.bsdfs[s.shapes[3].bsdf].type, BsdfType::Null);
    EXPECT_EQ(s.bsdfs[s.shapes[4].bsdf].weight, 1.0f);  // clamped to [0, 1] as Mitsuba
}

TEST(LayeredBsdf, UnreadParametersWarn) {
    Scene s;
    std::vector<std::string> warnings;
    shapeBsdf(R"(<bsdf type="mask"><float name="opacty" value="0.3"/>
                 <bsdf type="diffuse"/></bsdf>)",
              s, &warnings);
    EXPECT_TRUE(hasWarning(warnings, {"opacty"}));
}

TEST(LayeredBsdf, Refusals) {
    TempDir dir;
    auto bad = [&](const std::string& bsdf, int line, const std::string& reason) {
        std::string path =
            dir.write("b.xml", sceneXml("<shape type=\"rectangle\">\n" + bsdf + "\n</shape>"));
        expectError([&] { loadScene(path); }, "b.xml", line, reason);
    };
    bad("<bsdf type=\"roughplastic\">\n<float name=\"alpha_u\" value=\"0.1\"/>"
        "<float name=\"alpha_v\" value=\"0.2\"/></bsdf>",
        4, "anisotropic roughness (alpha_u != alpha_v) is not supported by roughplastic");
    bad("<bsdf type=\"roughplastic\">\n<float name=\"int_ior\" value=\"1.000277\"/></bsdf>", 4,
        "int_ior and ext_ior must differ");
    bad("<bsdf type=\"roughplastic\">\n<string name=\"distribution\" value=\"phong\"/></bsdf>", 5,
        "must be 'beckmann' or 'ggx', not 'phong'");
    bad("<bsdf type=\"blendbsdf\">\n<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>", 4,
        "needs a 'weight' (Mitsuba 3 has no default for it)");
    bad("<bsdf type=\"blendbsdf\">\n<float name=\"weight\" value=\"0.5\"/><bsdf type=\"diffuse\"/>"
        "</bsdf>", 4, "needs two nested bsdfs, got 1");
    bad("<bsdf type=\"mask\">\n<bsdf type=\"diffuse\"/><bsdf type=\"null\"/></bsdf>", 4,
        "needs exactly one nested bsdf, got 2");
    bad("<bsdf type=\"mask\"/>", 4, "needs exactly one nested bsdf, got 0");
    bad("<bsdf type=\"null\">\n<bsdf type=\"diffuse\"/></bsdf>", 5, "cannot contain a <bsdf>");
    // Mitsuba's twosided takes no BSDF with a transmission (or null) component.
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf></bsdf>", 5,
        "cannot wrap a bsdf that transmits light (mask)");
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"null\"/></bsdf>", 5,
        "cannot wrap a bsdf that transmits light (null)");
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/>"
        "<bsdf type=\"diffuse\"/><bsdf type=\"dielectric\"/></bsdf></bsdf>", 5,
        "cannot wrap a bsdf that transmits light (blendbsdf)");
    // A tree the kernels cannot walk: 16 leaves in blends nested four deep.
    std::string deep = "<bsdf type=\"diffuse\"/>";
    for (int i = 0; i < 4; ++i)
        deep = "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/>" + deep + deep +
               "</bsdf>";
    bad(deep, 4, "nests too many bsdfs: 16 leaves in 4 levels");
    std::string tall = "<bsdf type=\"diffuse\"/>";
    for (int i = 0; i < 9; ++i)
        tall = "<bsdf type=\"mask\">" + tall + "</bsdf>";
    bad(tall, 4, "nests too many bsdfs: 1 leaves in 9 levels");
}

TEST(LayeredBsdf, PrincipledDefaultsAndLobes) {
    Scene s;
    const Bsdf& d = s.bsdfs[shapeBsdf(R"(<bsdf type="principled"/>)", s)];
    EXPECT_EQ(d.type, BsdfType::Principled);
    EXPECT_EQ(d.reflectance.g, 0.5f);
    EXPECT_EQ(d.principled.roughness, 0.5f);
    EXPECT_NEAR(d.principled.eta, 1.5f, 1e-6f);  // specular 0.5
    EXPECT_FALSE(d.principled.hasMetallic || d.principled.hasSheen ||
                 d.principled.hasClearcoat || d.principled.hasSpecTrans);
    Scene t;
    const Bsdf& b = t.bsdfs[shapeBsdf(R"(<bsdf type="principled">
        <rgb name="base_color" value="0.1, 0.2, 0.3"/><float name="roughness" value="0.2"/>
        <float name="metallic" value="0.4"/><float name="spec_tint" value="0.1"/>
        <float name="anisotropic" value="0.6"/><float name="sheen" value="0"/>
        <float name="sheen_tint" value="0.3"/><float name="clearcoat" value="0.7"/>
        <float name="clearcoat_gloss" value="0.8"/><float name="spec_trans" value="0.9"/>
        <float name="flatness" value="0.2"/><float name="eta" value="1"/>
        <float name="main_specular_sampling_rate" value="2"/></bsdf>)", t)];
    const PrincipledParams& q = b.principled;
    EXPECT_EQ(b.reflectance.b, 0.3f);
    EXPECT_EQ(q.roughness, 0.2f);
    EXPECT_TRUE(q.hasMetallic && q.hasSpecTint && q.hasAnisotropic && q.hasSheenTint &&
                q.hasClearcoat && q.hasSpecTrans && q.hasFlatness);
    EXPECT_FALSE(q.hasSheen);  // given as the float 0: Mitsuba's get_flag leaves the lobe off
    EXPECT_EQ(q.metallic, 0.4f);
    EXPECT_EQ(q.clearcoatGloss, 0.8f);
    EXPECT_EQ(q.specTrans, 0.9f);
    EXPECT_EQ(q.eta, 1.001f);  // eta 1 cannot transmit: Mitsuba's 1.001
    EXPECT_EQ(q.specRate, 2.0f);
}

TEST(LayeredBsdf, PrincipledRefusals) {
    TempDir dir;
    auto bad = [&](const std::string& bsdf, int line, const std::string& reason) {
        std::string path =
            dir.write("b.xml", sceneXml("<shape type=\"rectangle\">\n" + bsdf + "\n</shape>"));
        expectError([&] { loadScene(path); }, "b.xml", line, reason);
    };
    bad("<bsdf type=\"principled\">\n<float name=\"eta\" value=\"1.5\"/>"
        "<float name=\"specular\" value=\"0.5\"/></bsdf>",
        4, "give either 'eta' or 'specular', not both");
    bad("<bsdf type=\"principled\">\n<float name=\"metallic\" value=\"1.5\"/></bsdf>", 5,
        "'metallic' must lie in [0, 1]");
    bad("<bsdf type=\"principled\">\n<float name=\"eta\" value=\"-1\"/></bsdf>", 5,
        "'eta' must be positive");
    // Mitsuba's twosided refuses a transmissive principled.
    bad("<bsdf type=\"twosided\">\n<bsdf type=\"principled\"><float name=\"spec_trans\" "
        "value=\"0.5\"/></bsdf></bsdf>", 5, "cannot wrap a bsdf that transmits light (principled)");
}

// Eight leaves (the kernels' bound) load, and the blend of blends evaluates to its mixture.
TEST(LayeredBsdf, EightLeavesLoad) {
    std::string tree = "<bsdf type=\"diffuse\"><float name=\"reflectance\" value=\"0.8\"/></bsdf>";
    for (int i = 0; i < 3; ++i)
        tree = "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/>" + tree + tree +
               "</bsdf>";
    Scene s;
    const uint32_t id = shapeBsdf(tree, s);
    SurfaceInteraction si;
    si.ns = si.ng = Vec3f(0, 0, 1);
    const Vec3f w = normalize(Vec3f(0.2f, 0.1f, 1));
    const Spectrum f = evalBsdf(Span<const Bsdf>(s.bsdfs), id, si, w, w);
    EXPECT_NEAR(f.r, 0.8f * w.z / kPi, 1e-6f);
}

}  // namespace
}  // namespace caustica::test
