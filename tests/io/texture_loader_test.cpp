// texture_loader_test.cpp — <texture> plugins (bitmap, checkerboard, rawconstant), textured BSDF
// parameters, bumpmap and normalmap: parameters, defaults, references and errors.
#include <Imath/half.h>

#include "caustica/io/image_io.h"
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

}  // namespace
}  // namespace caustica::test
