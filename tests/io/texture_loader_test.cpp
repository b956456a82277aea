// texture_loader_test.cpp — <texture> plugins (bitmap, checkerboard with nested textures,
// rawconstant), textured BSDF parameters (principled weights, conductor eta/k), the spot's texture,
// bumpmap and normalmap: parameters, defaults, references, errors, and bitmaps
// smaller than 2 x 2 against Mitsuba.
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "caustica/io/image_io.h"
#include "caustica/scene/texture.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

/// A 2 x 2 8-bit PNG with sRGB-encoded values 0, 64/255, 128/255, 1 (grey) in `dir`.
std::string writeTexture(const TempDir& dir, const std::string& name = "tex.png") {
    Image img(2, 2);
    const float encoded[4] = {0.0f, 64 / 255.0f, 128 / 255.0f, 1.0f};
    for (int i = 0; i < 4; ++i) img.set(i % 2, i / 2, Spectrum(srgbToLinear(encoded[i])));
    const std::string path = dir.path(name);
    writeImage(path, img);
    return path;
}

std::string diffuseWith(const std::string& texture) {
    return sceneXml("<shape type=\"sphere\"><bsdf type=\"diffuse\">\n" + texture +
                    "\n</bsdf></shape>");
}

float half(float v) { return float(Imath::half(v)); }

TEST(TextureLoader, BitmapDefaultsDecodeSrgbAndRoundToHalf) {
    TempDir dir;
    writeTexture(dir);
    const Scene s = loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance">
        <string name="filename" value="tex.png"/></texture>)"));
    ASSERT_EQ(s.textures.size(), 1u);
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.type, TextureType::Bitmap);
    EXPECT_EQ(t.width, 2);
    EXPECT_EQ(t.height, 2);
    EXPECT_EQ(t.filter, TextureFilter::Bilinear);
    EXPECT_EQ(t.wrap, TextureWrap::Repeat);
    ASSERT_EQ(s.texels.size(), 4u);
    EXPECT_EQ(s.texels[1].r, half(srgbToLinear(64 / 255.0f)));
    EXPECT_EQ(s.texels[3].g, 1.0f);
    const Bsdf& b = s.bsdfs[s.shapes[0].bsdf];
    ASSERT_EQ(b.numTextures, 1u);
    EXPECT_EQ(b.textures[0].param, BsdfParam::Reflectance);
    EXPECT_EQ(b.textures[0].texture, 0u);
    EXPECT_NEAR(t.mean, (s.texels[0].r + s.texels[1].r + s.texels[2].r + s.texels[3].r) / 4, 1e-6);
}

TEST(TextureLoader, BitmapOptions) {
    TempDir dir;
    writeTexture(dir);
    const Scene s = loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance">
        <string name="filename" value="tex.png"/>
        <boolean name="raw" value="true"/>
        <string name="filter_type" value="nearest"/>
        <string name="wrap_mode" value="mirror"/>
        <string name="format" value="variant"/>
        <transform name="to_uv"><scale x="2" y="3"/><translate x="0.5" y="0.25"/></transform>
        </texture>)"));
    const Texture& t = s.textures[0];
    EXPECT_EQ(t.filter, TextureFilter::Nearest);
    EXPECT_EQ(t.wrap, TextureWrap::Mirror);
    EXPECT_EQ(s.texels[1].r, 64 / 255.0f);  // raw: the stored value; variant: no half rounding
    const Float expected[6] = {2, 0, 0.5f, 0, 3, 0.25f};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(t.toUv[i], expected[i]) << i;
    const Scene clamp = loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance">
        <string name="filename" value="tex.png"/><string name="wrap_mode" value="clamp"/>
        </texture>)"));
    EXPECT_EQ(clamp.textures[0].wrap, TextureWrap::Clamp);
}

TEST(TextureLoader, CheckerboardRawConstantAndReferences) {
    TempDir dir;
    const Scene s = loadXml(dir, sceneXml(R"(
        <texture type="checkerboard" id="checks">
            <rgb name="color0" value="0.1, 0.2, 0.3"/>
            <transform name="to_uv"><scale value="4"/></transform>
        </texture>
        <shape type="sphere"><bsdf type="diffuse"><ref name="reflectance" id="checks"/></bsdf></shape>
        <shape type="sphere"><bsdf type="plastic"><ref name="diffuse_reflectance" id="checks"/></bsdf></shape>
        <shape type="sphere"><bsdf type="diffuse">
            <texture type="rawconstant" name="reflectance"><float name="value" value="0.25"/></texture>
        </bsdf></shape>
        <shape type="sphere"><bsdf type="diffuse"><texture type="checkerboard" name="reflectance"/></bsdf></shape>)"));
    ASSERT_EQ(s.textures.size(), 3u);  // the referenced checkerboard is one record
    const Texture& c = s.textures[0];
    EXPECT_EQ(c.type, TextureType::Checkerboard);
    EXPECT_NEAR(c.value.b, 0.3f, 1e-7);
    EXPECT_EQ(c.value1.r, 0.2f);  // Mitsuba's default color1
    EXPECT_EQ(c.toUv[0], 4);
    EXPECT_EQ(s.bsdfs[s.shapes[0].bsdf].textures[0].texture, 0u);
    const Bsdf& plastic = s.bsdfs[s.shapes[1].bsdf];
    ASSERT_EQ(plastic.numTextures, 1u);
    EXPECT_EQ(plastic.textures[0].param, BsdfParam::Diffuse);
    // The specular sampling weight uses the texture's mean, as Mitsuba's plastic does.
    EXPECT_NEAR(plastic.specularWeight, 1 / (1 + c.mean), 1e-6);
    const Bsdf& constant = s.bsdfs[s.shapes[2].bsdf];
    EXPECT_EQ(constant.numTextures, 0u);  // rawconstant is folded into the value
    EXPECT_EQ(constant.reflectance.g, 0.25f);
    EXPECT_EQ(s.textures[2].value.r, 0.4f);  // default color0
}

// Mitsuba's bounds on colour values: an <rgb> reflectance lies in [0, 1] (refused otherwise, see
// the bad-scene corpus), but emission, the conductor's eta and k, and a rawconstant's <vector> do not.
TEST(TextureLoader, ColoursBeyondOneWhereMitsubaAllowsThem) {
    TempDir dir;
    const Scene s = loadXml(dir, sceneXml(R"(
        <shape type="sphere"><bsdf type="diffuse">
            <texture type="rawconstant" name="reflectance"><vector name="value" x="0.2" y="0.3" z="1.5"/></texture>
        </bsdf></shape>
        <shape type="sphere"><bsdf type="conductor">
            <rgb name="eta" value="0.2, 0.9, 1.4"/><rgb name="k" value="3.9, 2.4, 1.6"/>
        </bsdf></shape>
        <shape type="sphere"><emitter type="area"><rgb name="radiance" value="10, 5, 2"/></emitter></shape>)"));
    const Spectrum constant = s.bsdfs[s.shapes[0].bsdf].reflectance;
    EXPECT_EQ(constant.r, 0.2f);
    EXPECT_EQ(constant.b, 1.5f);
    EXPECT_EQ(s.bsdfs[s.shapes[1].bsdf].k.r, 3.9f);
    EXPECT_EQ(s.lights[0].radiance.r, 10.0f);
}

TEST(TextureLoader, RoughnessTextures) {
    TempDir dir;
    writeTexture(dir);
    const std::string tex = R"(<texture type="bitmap" name="NAME"><string name="filename" value="tex.png"/></texture>)";
    auto named = [&](const std::string& n) {
        std::string s = tex;
        return s.replace(s.find("NAME"), 4, n);
    };
    const Scene s = loadXml(dir, sceneXml(
        "<shape type=\"sphere\"><bsdf type=\"roughconductor\">" + named("alpha") +
        "</bsdf></shape><shape type=\"sphere\"><bsdf type=\"roughdielectric\">" +
        named("alpha_u") + "<float name=\"alpha_v\" value=\"0.3\"/>" +
        named("specular_transmittance") + "</bsdf></shape>"));
    const Bsdf& rc = s.bsdfs[s.shapes[0].bsdf];
    ASSERT_EQ(rc.numTextures, 1u);
    EXPECT_EQ(rc.textures[0].param, BsdfParam::Alpha);
    const Bsdf& rd = s.bsdfs[s.shapes[1].bsdf];
    ASSERT_EQ(rd.numTextures, 2u);
    EXPECT_EQ(rd.textures[0].param, BsdfParam::Transmittance);  // read in the builder's order
    EXPECT_EQ(rd.textures[1].param, BsdfParam::AlphaU);
    EXPECT_EQ(rd.alphaV, 0.3f);
    expectError([&] { loadXml(dir, sceneXml("<shape type=\"sphere\"><bsdf type=\"roughconductor\">" +
                                            named("alpha_u") + "</bsdf></shape>")); },
                "scene.xml", 3, "'alpha_u' and 'alpha_v' must be given together");
    expectError([&] { loadXml(dir, sceneXml("<shape type=\"sphere\"><bsdf type=\"roughconductor\">" +
                                            named("alpha") + "<float name=\"alpha\" value=\"0.2\"/></bsdf></shape>")); },
                "scene.xml", 3, "'alpha' is given both as a value and as a texture");
}

TEST(TextureLoader, Errors) {
    TempDir dir;
    writeTexture(dir);
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance"><string name="filename" value="tex.png"/>
        <string name="filter_type" value="trilinear"/></texture>)")); },
                "scene.xml", 5, "must be 'bilinear' or 'nearest', not 'trilinear'");
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance"><string name="filename" value="tex.png"/>
        <string name="wrap_mode" value="border"/></texture>)")); },
                "scene.xml", 5, "must be 'repeat', 'mirror' or 'clamp', not 'border'");
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance"><string name="filename" value="none.png"/></texture>)")); },
                "scene.xml", 4, "none.png");
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectance"/>)")); },
                "scene.xml", 4, "missing required parameter 'filename'");
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="bitmap" name="reflectanse"><string name="filename" value="tex.png"/></texture>)")); },
                "scene.xml", 4, "texture 'reflectanse' is not a textured parameter of this plugin");
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="marble" name="reflectance"/>)")); },
                "scene.xml", 4, "unsupported texture type 'marble'");
    expectError([&] { loadXml(dir, sceneXml(R"(<shape type="sphere"><bsdf type="twosided"><bsdf type="diffuse"/>
        <texture type="checkerboard" name="reflectance"/></bsdf></shape>)")); },
                "scene.xml", 4, "is not a textured parameter of this plugin");
    std::vector<std::string> warnings;
    loadXml(dir, sceneXml(R"(<texture type="checkerboard" id="unused"/><shape type="sphere"/>)"),
            &warnings);
    EXPECT_TRUE(hasWarning(warnings, {"texture", "is declared but never used"}));
}

TEST(TextureLoader, NestedCheckerboards) {
    TempDir dir;
    writeTexture(dir);
    const Scene s = loadXml(dir, sceneXml(R"(
        <texture type="checkerboard" id="inner"><float name="color1" value="0.6"/></texture>
        <shape type="sphere"><bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <ref name="color0" id="inner"/>
            <texture type="bitmap" name="color1"><string name="filename" value="tex.png"/></texture>
        </texture></bsdf></shape>
        <shape type="sphere"><bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <texture type="rawconstant" name="color1"><float name="value" value="0.7"/></texture>
        </texture></bsdf></shape>)"));
    ASSERT_EQ(s.textures.size(), 5u);  // inner, bitmap, outer, rawconstant, second outer
    const Texture& outer = s.textures[2];
    EXPECT_EQ(outer.child0, 0u);  // children are built before their parent
    EXPECT_EQ(outer.child1, 1u);
    // Mitsuba's mean: the average of the colours' means.
    EXPECT_NEAR(outer.mean, (s.textures[0].mean + s.textures[1].mean) / 2, 1e-7);
    EXPECT_NEAR(s.textures[0].mean, 0.5f, 1e-7);
    const Texture& folded = s.textures[4];  // a constant child is kept as a value
    EXPECT_EQ(folded.child1, kNoTexture);
    EXPECT_EQ(folded.value1.r, 0.7f);
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="checkerboard" name="reflectance">
        <texture type="checkerboard" name="colour0"/></texture>)")); },
                "scene.xml", 5, "texture 'colour0' is not a parameter of checkerboard");
    expectError([&] { loadXml(dir, diffuseWith(R"(<texture type="checkerboard" name="reflectance">
        <float name="color0" value="0.3"/><texture type="checkerboard" name="color0"/></texture>)")); },
                "scene.xml", 5, "'color0' is given both as a value and as a texture");
}

TEST(TextureLoader, PrincipledAndConductorTextures) {
    TempDir dir;
    writeTexture(dir);
    auto tex = [](const std::string& name) {
        return R"(<texture type="bitmap" name=")" + name +
               R"("><string name="filename" value="tex.png"/></texture>)";
    };
    const char* weights[] = {"roughness", "anisotropic", "metallic", "spec_tint", "sheen",
                             "sheen_tint", "clearcoat", "clearcoat_gloss", "spec_trans",
                             "flatness"};
    std::string principled = tex("base_color");
    for (const char* w : weights) principled += tex(w);
    const Scene s = loadXml(dir, sceneXml(
        "<shape type=\"sphere\"><bsdf type=\"principled\">" + principled +
        "</bsdf></shape><shape type=\"sphere\"><bsdf type=\"roughconductor\">" + tex("eta") +
        tex("k") + "</bsdf></shape>"));
    const Bsdf& p = s.bsdfs[s.shapes[0].bsdf];
    ASSERT_EQ(p.numTextures, 11u);
    const BsdfParam expected[] = {BsdfParam::Reflectance, BsdfParam::Roughness,
                                  BsdfParam::Anisotropic, BsdfParam::SpecTrans,
                                  BsdfParam::Sheen,       BsdfParam::SheenTint,
                                  BsdfParam::Flatness,    BsdfParam::SpecTint,
                                  BsdfParam::Metallic,    BsdfParam::Clearcoat,
                                  BsdfParam::ClearcoatGloss};
    for (uint32_t i = 0; i < 11; ++i) EXPECT_EQ(p.textures[i].param, expected[i]) << i;
    // A texture turns its lobe on (Mitsuba's get_flag).
    EXPECT_TRUE(p.principled.hasAnisotropic && p.principled.hasSpecTrans &&
                p.principled.hasSheen && p.principled.hasSheenTint && p.principled.hasFlatness &&
                p.principled.hasSpecTint && p.principled.hasMetallic && p.principled.hasClearcoat);
    const Bsdf& rc = s.bsdfs[s.shapes[1].bsdf];
    ASSERT_EQ(rc.numTextures, 2u);
    EXPECT_EQ(rc.textures[0].param, BsdfParam::Eta);
    EXPECT_EQ(rc.textures[1].param, BsdfParam::K);
    // Mitsuba 3.9.1 reads principled's specular and eta and roughplastic's alpha as floats.
    expectError([&] { loadXml(dir, sceneXml("<shape type=\"sphere\"><bsdf type=\"principled\">\n" +
                                            tex("specular") + "</bsdf></shape>")); },
                "scene.xml", 4, "texture 'specular' is not a textured parameter of this plugin");
    expectError([&] { loadXml(dir, sceneXml("<shape type=\"sphere\"><bsdf type=\"roughplastic\">" +
                                            tex("alpha") + "</bsdf></shape>")); },
                "scene.xml", 3, "'alpha' must be a float for roughplastic");
    expectError([&] { loadXml(dir, sceneXml("<shape type=\"sphere\"><bsdf type=\"conductor\">" +
                                            tex("eta") +
                                            "<string name=\"material\" value=\"Au\"/></bsdf></shape>")); },
                "scene.xml", 3, "cannot be combined with 'eta'/'k'");
}

TEST(TextureLoader, SpotTexture) {
    TempDir dir;
    writeTexture(dir);
    const Scene s = loadXml(dir, sceneXml(R"(<emitter type="spot">
        <float name="cutoff_angle" value="30"/>
        <texture type="bitmap" name="texture"><string name="filename" value="tex.png"/></texture>
    </emitter><emitter type="spot"/>)"));
    ASSERT_EQ(s.lights.size(), 2u);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.lights[0].texture, 0u);
    EXPECT_NEAR(s.lights[0].uvFactor, std::tan(30 * M_PI / 180), 1e-6);
    EXPECT_EQ(s.lights[1].texture, kNoTexture);
    expectError([&] { loadXml(dir, sceneXml(R"(<emitter type="spot">
        <rgb name="texture" value="0.5"/></emitter>)")); },
                "scene.xml", 4, "must be a spatially varying texture");
}

TEST(TextureLoader, BumpAndNormalMaps) {
    TempDir dir;
    writeTexture(dir);
    const Scene s = loadXml(dir, sceneXml(R"(
        <shape type="sphere"><bsdf type="twosided"><bsdf type="bumpmap">
            <texture type="bitmap" name="arbitrary"><string name="filename" value="tex.png"/>
                <boolean name="raw" value="true"/></texture>
            <float name="scale" value="0.5"/>
            <bsdf type="roughconductor"/>
        </bsdf></bsdf></shape>
        <shape type="sphere"><bsdf type="normalmap">
            <texture type="bitmap" name="normalmap"><string name="filename" value="tex.png"/></texture>
            <boolean name="use_shadowing_function" value="false"/>
            <boolean name="flip_invalid_normals" value="false"/>
            <bsdf type="diffuse"/>
        </bsdf></shape>)"));
    const Bsdf& two = s.bsdfs[s.shapes[0].bsdf];
    ASSERT_EQ(two.type, BsdfType::TwoSided);
    const Bsdf& bump = s.bsdfs[two.front];
    EXPECT_EQ(bump.type, BsdfType::BumpMap);
    EXPECT_EQ(bump.bumpScale, 0.5f);
    EXPECT_TRUE(bump.flipInvalidNormals);  // Mitsuba 3.9.1's defaults
    EXPECT_TRUE(bump.shadowTerminator);
    EXPECT_EQ(s.bsdfs[bump.front].type, BsdfType::RoughConductor);
    EXPECT_EQ(s.textures[bump.frameTexture].type, TextureType::Bitmap);
    const Bsdf& normal = s.bsdfs[s.shapes[1].bsdf];
    EXPECT_EQ(normal.type, BsdfType::NormalMap);
    EXPECT_EQ(s.bsdfs[normal.front].type, BsdfType::Diffuse);
    EXPECT_EQ(normal.frameTexture, 1u);
    EXPECT_FALSE(normal.flipInvalidNormals);
    EXPECT_FALSE(normal.shadowTerminator);

    expectError([&] { loadXml(dir, sceneXml(R"(<shape type="sphere"><bsdf type="bumpmap">
        <texture type="checkerboard" name="h"/><bsdf type="diffuse"/></bsdf></shape>)")); },
                "scene.xml", 4, "the height field must be a bitmap");
    expectError([&] { loadXml(dir, sceneXml(R"(<shape type="sphere"><bsdf type="bumpmap">
        <bsdf type="diffuse"/></bsdf></shape>)")); },
                "scene.xml", 3, "needs exactly one nested texture");
    expectError([&] { loadXml(dir, sceneXml(R"(<shape type="sphere"><bsdf type="normalmap">
        <texture type="bitmap" name="normals"><string name="filename" value="tex.png"/></texture>
        <bsdf type="diffuse"/></bsdf></shape>)")); },
                "scene.xml", 3, "needs a nested texture named 'normalmap'");
    expectError([&] { loadXml(dir, sceneXml(R"(<shape type="sphere"><bsdf type="bumpmap">
        <texture type="bitmap" name="h"><string name="filename" value="tex.png"/></texture>
        <bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="tex.png"/></texture>
        <bsdf type="diffuse"/></bsdf></bsdf></shape>)")); },
                "scene.xml", 5, "cannot nest a bumpmap or normalmap in another one");
}

/// A bitmap smaller than 2 x 2 evaluated as Mitsuba 3.9.1 does (scalar_rgb, texture.eval at the
/// uvs below; it resamples the image to at least 2 x 2, repeating the lone row or column).
struct MitsubaSmallBitmap {
    int width, height;
    std::vector<int> bytes;  // 8-bit sRGB, row by row
    const char* filter;
    const char* wrap;
    std::vector<Spectrum> expected;  // at kSmallBitmapUvs
};

const Vec2f kSmallBitmapUvs[5] = {{0.1f, 0.2f}, {0.5f, 0.5f}, {0.9f, 0.77f}, {0.33f, 0.95f},
                                  {1.3f, -0.2f}};

TEST(TextureLoader, BitmapsSmallerThan2x2AreEvaluatedAsMitsuba) {
    const std::vector<int> row = {243, 8, 36, 210, 242, 63, 79, 222, 108};
    const std::vector<int> column = {69, 211, 65, 104, 164, 140, 21, 7, 221};
    const Spectrum r0(0.896269f, 0.002428f, 0.017642f), r1(0.64448f, 0.887923f, 0.049707f),
        r2(0.078187f, 0.730461f, 0.14996f);
    const Spectrum c0(0.059511f, 0.651406f, 0.052861f), c1(0.138432f, 0.371238f, 0.262251f),
        c2(0.007499f, 0.002125f, 0.723055f);
    const Spectrum one(0.191202f, 0.226966f, 0.533277f);
    const MitsubaSmallBitmap cases[] = {
        {1, 1, {121, 131, 193}, "bilinear", "repeat", {one, one, one, one, one}},
        {1, 1, {121, 131, 193}, "nearest", "mirror", {one, one, one, one, one}},
        {3, 1, row, "bilinear", "repeat",
         {{0.732653f, 0.148035f, 0.044106f}, r1, {0.241804f, 0.584854f, 0.123496f},
          {0.772892f, 0.436321f, 0.033354f}, {0.795553f, 0.356626f, 0.030468f}}},
        {3, 1, row, "bilinear", "clamp", {r0, r1, r2, {0.772892f, 0.436321f, 0.033354f}, r2}},
        {3, 1, row, "nearest", "mirror", {r0, r1, r2, r0, r2}},
        {1, 3, column, "bilinear", "mirror",
         {{0.067403f, 0.623389f, 0.0738f}, c1, {0.032376f, 0.072256f, 0.635502f}, c2,
          {0.067403f, 0.623389f, 0.0738f}}},
        {1, 3, column, "nearest", "repeat", {c0, c1, c2, c2, c2}},
    };
    for (const MitsubaSmallBitmap& c : cases) {
        SCOPED_TRACE(std::to_string(c.width) + "x" + std::to_string(c.height) + " " + c.filter +
                     " " + c.wrap);
        TempDir dir;
        Image img(c.width, c.height);
        const auto decode = [&](int j) { return srgbToLinear(float(c.bytes[size_t(j)]) / 255); };
        for (int i = 0; i < c.width * c.height; ++i)
            img.set(i % c.width, i / c.width, {decode(3 * i), decode(3 * i + 1), decode(3 * i + 2)});
        writeImage(dir.path("small.png"), img);
        const std::string xml = std::string(R"(<texture type="bitmap" name="reflectance">
            <string name="filename" value="small.png"/><string name="filter_type" value=")") +
                                c.filter + R"("/><string name="wrap_mode" value=")" + c.wrap +
                                R"("/></texture>)";
        const Scene s = loadXml(dir, diffuseWith(xml));
        ASSERT_EQ(s.textures.size(), 1u);
        EXPECT_EQ(s.textures[0].width, std::max(c.width, 2));
        EXPECT_EQ(s.textures[0].height, std::max(c.height, 2));
        for (int k = 0; k < 5; ++k) {
            const Spectrum v = evalTexture(s.view().textureView(), 0, kSmallBitmapUvs[k]);
            // Mitsuba 3.9.1 keeps 8-bit texels as bytes; caustica rounds them to half floats
            // (relative error below 2^-12).
            EXPECT_NEAR(v.r, c.expected[k].r, 3e-4) << "uv " << k;
            EXPECT_NEAR(v.g, c.expected[k].g, 3e-4) << "uv " << k;
            EXPECT_NEAR(v.b, c.expected[k].b, 3e-4) << "uv " << k;
        }
    }
}

}  // namespace
}  // namespace caustica::test
