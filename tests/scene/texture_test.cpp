// texture_test.cpp — texture evaluation (filters, wrap modes, to_uv, checkerboard and nested
// checkerboards, eval_1, gradient), textured BSDF parameters (principled weights, conductor
// eta/k), the spot light's texture, and the dp/du shading frame of meshes and spheres.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/light_delta.h"
#include "caustica/scene/texture.h"
#include "scene/bsdf_test_util.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

/// A 3 x 2 bitmap with distinct texels: texel (x, y) = (x, y, 10 + x + 3y) / 16.
struct TestBitmap {
    std::vector<Texture> textures;
    std::vector<Spectrum> texels;
    explicit TestBitmap(TextureFilter filter, TextureWrap wrap) {
        Texture t;
        t.type = TextureType::Bitmap;
        t.width = 3;
        t.height = 2;
        t.filter = filter;
        t.wrap = wrap;
        textures.push_back(t);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x)
                texels.push_back(Spectrum(Float(x), Float(y), Float(10 + x + 3 * y)) * (1.0f / 16));
    }
    TextureView view() const { return {textures, texels}; }
    Spectrum texel(int x, int y) const { return texels[size_t(y * 3 + x)]; }
};

void expectNear(Spectrum a, Spectrum b, Float tol = 1e-6f) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

void expectNear(Vec3f a, Vec3f b, Float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

/// Mirror wrap written independently: period 2·res, the second half reversed.
int mirrorReference(int pos, int res) {
    int m = ((pos % (2 * res)) + 2 * res) % (2 * res);
    return m < res ? m : 2 * res - 1 - m;
}

TEST(Texture, WrapIndexMatchesDrJit) {
    using texture_detail::wrapIndex;
    for (int res : {1, 2, 3, 5})
        for (int pos = -20; pos <= 20; ++pos) {
            EXPECT_EQ(wrapIndex(pos, res, TextureWrap::Repeat), ((pos % res) + res) % res);
            EXPECT_EQ(wrapIndex(pos, res, TextureWrap::Mirror), mirrorReference(pos, res))
                << pos << " " << res;
            EXPECT_EQ(wrapIndex(pos, res, TextureWrap::Clamp), std::min(std::max(pos, 0), res - 1));
        }
}

TEST(Texture, NearestReadsTheTexelUnderUvWithRowZeroAtTop) {
    const TestBitmap bm(TextureFilter::Nearest, TextureWrap::Repeat);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            const Vec2f uv((Float(x) + 0.3f) / 3, (Float(y) + 0.7f) / 2);
            expectNear(evalTexture(bm.view(), 0, uv), bm.texel(x, y));
        }
}

TEST(Texture, BilinearInterpolatesBetweenTexelCentres) {
    const TestBitmap bm(TextureFilter::Bilinear, TextureWrap::Clamp);
    // At a texel centre: the texel; halfway between two centres: their mean.
    expectNear(evalTexture(bm.view(), 0, Vec2f(0.5f / 3, 0.25f)), bm.texel(0, 0));
    expectNear(evalTexture(bm.view(), 0, Vec2f(1.0f / 3, 0.25f)),
               (bm.texel(0, 0) + bm.texel(1, 0)) * 0.5f);
    expectNear(evalTexture(bm.view(), 0, Vec2f(1.5f / 3, 0.5f)),
               (bm.texel(1, 0) + bm.texel(1, 1)) * 0.5f);
    // A quarter of the way in x and y from texel (1, 0) towards (2, 1).
    const Spectrum expected = bm.texel(1, 0) * (0.75f * 0.75f) + bm.texel(2, 0) * (0.25f * 0.75f) +
                              bm.texel(1, 1) * (0.75f * 0.25f) + bm.texel(2, 1) * (0.25f * 0.25f);
    expectNear(evalTexture(bm.view(), 0, Vec2f(1.75f / 3, 0.375f)), expected);
}

TEST(Texture, WrapModesAtTheBorder) {
    // Nearest lookups one texel outside [0, 1): repeat wraps around, mirror and clamp repeat the
    // edge texel.
    const Vec2f left(-0.5f / 3, 0.25f), right(3.5f / 3, 0.25f);
    const TestBitmap repeat(TextureFilter::Nearest, TextureWrap::Repeat);
    expectNear(evalTexture(repeat.view(), 0, left), repeat.texel(2, 0));
    expectNear(evalTexture(repeat.view(), 0, right), repeat.texel(0, 0));
    expectNear(evalTexture(repeat.view(), 0, Vec2f(0.5f / 3 + 7, 0.25f - 3)), repeat.texel(0, 0));
    const TestBitmap mirror(TextureFilter::Nearest, TextureWrap::Mirror);
    expectNear(evalTexture(mirror.view(), 0, left), mirror.texel(0, 0));
    expectNear(evalTexture(mirror.view(), 0, right), mirror.texel(2, 0));
    expectNear(evalTexture(mirror.view(), 0, Vec2f(4.5f / 3, 0.25f)), mirror.texel(1, 0));
    const TestBitmap clamp(TextureFilter::Nearest, TextureWrap::Clamp);
    expectNear(evalTexture(clamp.view(), 0, Vec2f(-5, 9)), clamp.texel(0, 1));
    expectNear(evalTexture(clamp.view(), 0, Vec2f(5, -9)), clamp.texel(2, 0));
    // Bilinear with repeat at u = 0 blends the first and the last column.
    const TestBitmap bilinear(TextureFilter::Bilinear, TextureWrap::Repeat);
    expectNear(evalTexture(bilinear.view(), 0, Vec2f(0, 0.25f)),
               (bilinear.texel(0, 0) + bilinear.texel(2, 0)) * 0.5f);
    // Non-finite uv stays inside the texel array.
    const Spectrum nanValue = evalTexture(bilinear.view(), 0, Vec2f(NAN, INFINITY));
    EXPECT_TRUE(std::isfinite(nanValue.r));
}

TEST(Texture, ToUvTransformsBeforeTheLookup) {
    TestBitmap bm(TextureFilter::Nearest, TextureWrap::Repeat);
    Float* m = bm.textures[0].toUv;  // uv' = (2u + 0.5, v / 2)
    m[0] = 2, m[2] = 0.5f, m[4] = 0.5f;
    // u' = 2 · 0.1 + 0.5 = 0.7 -> x = 2; v' = 0.9 / 2 = 0.45 -> y = 0.
    expectNear(evalTexture(bm.view(), 0, Vec2f(0.1f, 0.9f)), bm.texel(2, 0));
}

TEST(Texture, CheckerboardAlternatesAsMitsuba) {
    std::vector<Texture> textures(1);
    textures[0].type = TextureType::Checkerboard;
    textures[0].value = Spectrum(0.4f);
    textures[0].value1 = Spectrum(0.2f);
    const TextureView view{textures, {}};
    // color0 where (frac(u) > .5) == (frac(v) > .5).
    EXPECT_EQ(evalTexture(view, 0, Vec2f(0.25f, 0.25f)).r, 0.4f);
    EXPECT_EQ(evalTexture(view, 0, Vec2f(0.75f, 0.25f)).r, 0.2f);
    EXPECT_EQ(evalTexture(view, 0, Vec2f(0.25f, 0.75f)).r, 0.2f);
    EXPECT_EQ(evalTexture(view, 0, Vec2f(0.75f, 0.75f)).r, 0.4f);
    EXPECT_EQ(evalTexture(view, 0, Vec2f(-0.25f, 0.25f)).r, 0.2f);  // frac(-0.25) = 0.75
    textures[0].toUv[0] = textures[0].toUv[4] = 2;  // four tiles per unit
    EXPECT_EQ(evalTexture(view, 0, Vec2f(0.375f, 0.125f)).r, 0.2f);
    // Mitsuba 3.9.1's eval_1 takes the other colour than eval (its mask test is mask.x != mask.y).
    EXPECT_FLOAT_EQ(evalTexture1(view, 0, Vec2f(0.1f, 0.1f)), 0.2f);
    EXPECT_FLOAT_EQ(evalTexture1(view, 0, Vec2f(0.375f, 0.125f)), 0.4f);
}

// Values printed by Mitsuba 3.9.1 (scalar_rgb, Python): a colour value's eval_1 is its mean
// (srgb texture), a bitmap's is its luminance.
TEST(Texture, Eval1OfColourValuesIsTheirMeanAndOfBitmapsTheLuminance) {
    std::vector<Texture> textures(1);
    textures[0].type = TextureType::Checkerboard;
    textures[0].value = Spectrum(0.9f, 0.1f, 0.1f);
    textures[0].value1 = Spectrum(0.1f, 0.1f, 0.9f);
    EXPECT_NEAR(evalTexture1({textures, {}}, 0, Vec2f(0.25f, 0.25f)), 0.3666667f, 1e-6f);
    std::vector<Spectrum> texels(4, Spectrum(0.9f, 0.1f, 0.1f));
    Texture bm;
    bm.type = TextureType::Bitmap;
    bm.width = bm.height = 2;
    textures.assign(1, bm);
    EXPECT_NEAR(evalTexture1({textures, texels}, 0, Vec2f(0.3f, 0.3f)), 0.2701368f, 1e-6f);
}

// Mitsuba 3.9.1 (checked through its Python bindings): a checkerboard's colours may be
// textures, evaluated at the outer interaction's uv (not at the outer to_uv's), and eval_1
// swaps the colours at every level.
TEST(Texture, NestedCheckerboardEvaluatesChildrenAtTheUnchangedUv) {
    std::vector<Texture> textures(3);
    textures[0].type = TextureType::Checkerboard;  // inner: 0.8 / 0.3
    textures[0].value = Spectrum(0.8f);
    textures[0].value1 = Spectrum(0.3f);
    textures[1].type = TextureType::Checkerboard;  // middle: inner / 0.1, to_uv scale 0.5
    textures[1].child0 = 0;
    textures[1].value1 = Spectrum(0.1f);
    textures[1].toUv[0] = textures[1].toUv[4] = 0.5f;
    textures[2].type = TextureType::Checkerboard;  // outer: 0.6 / middle
    textures[2].value = Spectrum(0.6f);
    textures[2].child1 = 1;
    const TextureView view{textures, {}};
    // middle at (0.6, 0.1): uv' = (0.3, 0.05) -> color0 = inner at (0.6, 0.1) -> color1 = 0.3
    // (at the scaled uv the inner board would give 0.8). Mitsuba: eval 0.3, eval_1 0.1.
    EXPECT_EQ(evalTexture(view, 1, Vec2f(0.6f, 0.1f)).r, 0.3f);
    EXPECT_FLOAT_EQ(evalTexture1(view, 1, Vec2f(0.6f, 0.1f)), 0.1f);
    EXPECT_EQ(evalTexture(view, 1, Vec2f(0.1f, 0.1f)).r, 0.8f);
    // Three levels: outer at (0.75, 0.25) is color1 -> middle -> inner -> 0.3; eval_1 at
    // (0.25, 0.25) takes outer color1 -> middle color1 = 0.1.
    EXPECT_EQ(evalTexture(view, 2, Vec2f(0.75f, 0.25f)).r, 0.3f);
    EXPECT_FLOAT_EQ(evalTexture1(view, 2, Vec2f(0.25f, 0.25f)), 0.1f);
    EXPECT_FLOAT_EQ(evalTexture1(view, 2, Vec2f(0.75f, 0.25f)), 0.6f);
}

TEST(Texture, GradientMatchesFiniteDifferencesOfTheLuminance) {
    TestBitmap bm(TextureFilter::Bilinear, TextureWrap::Repeat);
    Float* m = bm.textures[0].toUv;  // a rotation-and-scale to_uv exercises the transpose
    m[0] = 1.5f, m[1] = 0.5f, m[3] = -0.25f, m[4] = 2;
    const TextureView view = bm.view();
    TestBitmap plainTex(TextureFilter::Bilinear, TextureWrap::Repeat);
    const TextureView identity = plainTex.view();
    const double h = 1e-3;
    for (Vec2f uv : {Vec2f(0.11f, 0.13f), Vec2f(0.42f, 0.57f), Vec2f(0.83f, 0.29f)}) {
        // Mitsuba's definition (bitmap.cpp eval_1_grad): with d the partials of the luminance with
        // respect to the pixel coordinates at uv' = to_uv(uv), grad = res · (Jᵀ d).
        const Vec2f up(m[0] * uv.x + m[1] * uv.y, m[3] * uv.x + m[4] * uv.y);
        auto f = [&](double u, double v) {
            return double(evalTexture1(identity, 0, Vec2f(Float(u), Float(v))));
        };
        const double dx = (f(up.x + h, up.y) - f(up.x - h, up.y)) / (2 * h) / 3;
        const double dy = (f(up.x, up.y + h) - f(up.x, up.y - h)) / (2 * h) / 2;
        const Vec2f g = evalTextureGrad(view, 0, uv);
        EXPECT_NEAR(g.x, 3 * (m[0] * dx + m[3] * dy), 2e-3);
        EXPECT_NEAR(g.y, 2 * (m[1] * dx + m[4] * dy), 2e-3);
    }
    // Identity to_uv: the gradient is the exact derivative of the bilinear lookup.
    TestBitmap plain(TextureFilter::Bilinear, TextureWrap::Repeat);
    const TextureView pv = plain.view();
    for (Vec2f uv : {Vec2f(0.11f, 0.13f), Vec2f(0.42f, 0.57f), Vec2f(0.83f, 0.29f)}) {
        auto f = [&](double u, double v) {
            return double(evalTexture1(pv, 0, Vec2f(Float(u), Float(v))));
        };
        const Vec2f g = evalTextureGrad(pv, 0, uv);
        EXPECT_NEAR(g.x, (f(uv.x + h, uv.y) - f(uv.x - h, uv.y)) / (2 * h), 2e-3);
        EXPECT_NEAR(g.y, (f(uv.x, uv.y + h) - f(uv.x, uv.y - h)) / (2 * h), 2e-3);
    }
    // Nearest filtering and other textures have no gradient (Mitsuba returns zero).
    TestBitmap nearest(TextureFilter::Nearest, TextureWrap::Repeat);
    const Vec2f g = evalTextureGrad(nearest.view(), 0, Vec2f(0.4f, 0.4f));
    EXPECT_EQ(g.x, 0.0f);
    EXPECT_EQ(g.y, 0.0f);
}

TEST(Texture, TexturedBsdfParameterIsEvaluatedAtUv) {
    TestBitmap bm(TextureFilter::Nearest, TextureWrap::Repeat);
    std::vector<Bsdf> bsdfs{test::diffuse(Spectrum(0.5f))};
    bsdfs[0].textures[0] = {BsdfParam::Reflectance, 0};
    bsdfs[0].numTextures = 1;
    SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    si.textures = bm.view();
    const Vec3f wo = normalize(Vec3f(0.2f, 0.1f, 1)), wi = normalize(Vec3f(-0.3f, 0.2f, 1));
    for (int x = 0; x < 3; ++x) {
        si.uv = Vec2f((Float(x) + 0.5f) / 3, 0.75f);
        const Spectrum f = evalBsdf(bsdfs, 0, si, wo, wi);
        expectNear(f, bm.texel(x, 1) * (kInvPi * wi.z));
        BsdfSample bs;
        ASSERT_TRUE(sampleBsdf(bsdfs, 0, si, wo, 0.5f, Vec2f(0.3f, 0.6f), bs));
        expectNear(bs.weight, bm.texel(x, 1));
    }
}

/// A BSDF with its textured parameters evaluated must equal the BSDF built with those values.
void expectSameBsdf(const Bsdf& textured, const Bsdf& plain, const SurfaceInteraction& si) {
    const std::vector<Bsdf> a{textured}, b{plain};
    for (Vec3f wi : {normalize(Vec3f(-0.3f, 0.2f, 1)), normalize(Vec3f(0.6f, -0.1f, 0.4f)),
                     normalize(Vec3f(0.1f, 0.3f, -1))}) {
        const Vec3f wo = normalize(Vec3f(0.2f, 0.1f, 1));
        expectNear(evalBsdf(a, 0, si, wo, wi), evalBsdf(b, 0, si, wo, wi));
        EXPECT_NEAR(pdfBsdf(a, 0, si, wo, wi), pdfBsdf(b, 0, si, wo, wi), 1e-6f);
    }
    for (Float uLobe : {0.05f, 0.3f, 0.6f, 0.95f}) {
        BsdfSample sa, sb;
        const Vec3f wo = normalize(Vec3f(0.2f, 0.1f, 1));
        const bool oka = sampleBsdf(a, 0, si, wo, uLobe, Vec2f(0.3f, 0.6f), sa);
        ASSERT_EQ(oka, sampleBsdf(b, 0, si, wo, uLobe, Vec2f(0.3f, 0.6f), sb));
        if (!oka) continue;
        expectNear(sa.wi, sb.wi);
        expectNear(sa.weight, sb.weight);
    }
}

// Every principled weight may be a texture (eval_1 at si.uv), as in Mitsuba 3.9.1.
TEST(Texture, PrincipledWeightsAreTexturable) {
    const BsdfParam params[] = {BsdfParam::Roughness, BsdfParam::Anisotropic,
                                BsdfParam::Metallic,  BsdfParam::SpecTint,
                                BsdfParam::Sheen,     BsdfParam::SheenTint,
                                BsdfParam::Clearcoat, BsdfParam::ClearcoatGloss,
                                BsdfParam::SpecTrans, BsdfParam::Flatness};
    const Float values[] = {0.35f, 0.6f, 0.25f, 0.7f, 0.8f, 0.45f, 0.9f, 0.3f, 0.4f, 0.55f};
    std::vector<Texture> textures;
    for (Float v : values) {
        Texture t;
        t.type = TextureType::Checkerboard;  // eval_1 at uv (0.25, 0.25) reads color1
        t.value = Spectrum(0.0f);
        t.value1 = Spectrum(v);
        textures.push_back(t);
    }
    Bsdf plain;
    plain.type = BsdfType::Principled;
    plain.reflectance = Spectrum(0.7f, 0.3f, 0.2f);
    PrincipledParams& q = plain.principled;
    q.hasAnisotropic = q.hasMetallic = q.hasSpecTint = q.hasSheen = q.hasSheenTint = true;
    q.hasClearcoat = q.hasSpecTrans = q.hasFlatness = true;
    Bsdf textured = plain;
    for (int i = 0; i < 10; ++i) {
        *bsdf_detail::principledSlot(plain.principled, params[i]) = values[i];
        textured.textures[i] = {params[i], uint32_t(i)};
    }
    textured.numTextures = 10;
    SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    si.textures = {textures, {}};
    si.uv = Vec2f(0.25f, 0.25f);
    EXPECT_EQ(plain.principled.flatness, 0.55f);  // principledSlot reached every field
    EXPECT_EQ(plain.principled.roughness, 0.35f);
    expectSameBsdf(textured, plain, si);
}

// Conductor eta and k may be textures (eval at si.uv).
TEST(Texture, ConductorEtaAndKAreTexturable) {
    std::vector<Texture> textures(2);
    textures[0].value = Spectrum(0.2f, 0.9f, 1.1f);  // constant textures: eval returns the value
    textures[1].value = Spectrum(3.5f, 2.5f, 1.5f);
    const Bsdf plain = test::roughConductor(0.3f, 0.3f, textures[0].value, textures[1].value);
    Bsdf textured = test::roughConductor(0.3f, 0.3f);
    textured.textures[0] = {BsdfParam::Eta, 0};
    textured.textures[1] = {BsdfParam::K, 1};
    textured.numTextures = 2;
    SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    si.textures = {textures, {}};
    expectSameBsdf(textured, plain, si);
}

// Mitsuba's spot texture: uv = 0.5 + 0.5 (x, y) / (z tan(cutoff)) of the local direction.
TEST(Texture, SpotTextureIsLookedUpAtMitsubasConeUv) {
    TestBitmap bm(TextureFilter::Nearest, TextureWrap::Clamp);
    Light l;
    l.type = LightType::Spot;
    l.radiance = Spectrum(2.0f);
    const Float cutoff = Float(40 * M_PI / 180);
    l.cutoff = cutoff;
    l.cosCutoff = l.cosBeam = std::cos(cutoff);  // no falloff inside the cone
    l.uvFactor = std::tan(cutoff);
    l.localFromWorld[0] = Vec3f(1, 0, 0);
    l.localFromWorld[1] = Vec3f(0, 1, 0);
    l.localFromWorld[2] = Vec3f(0, 0, 1);
    l.texture = 0;
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 2; ++y) {
            const Float u = (Float(x) + 0.5f) / 3, v = (Float(y) + 0.5f) / 2;
            const Vec3f w = normalize(Vec3f((2 * u - 1) * l.uvFactor, (2 * v - 1) * l.uvFactor, 1));
            ASSERT_GT(w.z, l.cosCutoff);  // every texel centre lies inside the cone
            expectNear(spotIntensity(l, bm.view(), w), bm.texel(x, y) * 2.0f);
        }
    expectNear(spotIntensity(l, bm.view(), normalize(Vec3f(1, 0, 0.5f))), Spectrum(0.0f));
    l.texture = kNoTexture;
    expectNear(spotIntensity(l, bm.view(), Vec3f(0, 0, 1)), Spectrum(2.0f));
}

TEST(ShadingFrame, FollowsDpduAndFallsBackToTheNormalFrame) {
    SurfaceInteraction si = test::surfaceAt(normalize(Vec3f(0.2f, -0.1f, 1)));
    const Frame fallback = shadingFrame(si);  // dp/du unknown: coordinate_system(n)
    const Frame expected(si.ns);
    EXPECT_EQ(fallback.s.x, expected.s.x);
    EXPECT_EQ(fallback.t.y, expected.t.y);
    si.dpdu = Vec3f(3, 1, 0);
    const Frame f = shadingFrame(si);
    EXPECT_NEAR(dot(f.s, si.ns), 0, 1e-6);
    EXPECT_NEAR(length(f.s), 1, 1e-6);
    EXPECT_NEAR(length(cross(f.s, normalize(si.dpdu - si.ns * dot(si.ns, si.dpdu)))), 0, 1e-6);
    EXPECT_GT(dot(f.s, si.dpdu), 0);
    const Vec3f t = cross(f.n, f.s);
    EXPECT_NEAR(length(f.t - t), 0, 1e-6);
}

TEST(ShadingFrame, MeshAndSphereDpdu) {
    Scene scene;
    // A quad in z = 0 with uv = ((x + 1) / 2, (y + 1) / 2) and one without uvs.
    const uint32_t quad = test::addMesh(scene, {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}},
                                        {{0, 1, 2}, {0, 2, 3}});
    scene.shapes[quad].hasUVs = true;
    scene.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    test::addMesh(scene, {{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}}, {{0, 1, 2}});
    test::addSphere(scene, Vec3f(0, 0, 5), 2);
    const SceneView view = scene.view();
    Hit hit;
    hit.primId = 0;
    hit.b1 = 0.2f;
    hit.b2 = 0.3f;
    hit.t = 1;
    SurfaceInteraction si = computeInteraction(view, Ray{Vec3f(0, 0, 1), Vec3f(0, 0, -1), 10}, hit);
    EXPECT_NEAR(length(si.dpdu - Vec3f(2, 0, 0)), 0, 1e-5);  // x = 2u - 1
    EXPECT_NEAR(length(si.dpdv - Vec3f(0, 2, 0)), 0, 1e-5);
    EXPECT_NEAR(length(shadingFrame(si).s - Vec3f(1, 0, 0)), 0, 1e-6);
    hit.primId = 2;  // no uvs: coordinate_system of the face normal (Mitsuba)
    si = computeInteraction(view, Ray{Vec3f(0, 0, 3), Vec3f(0, 0, -1), 10}, hit);
    const Frame face(Vec3f(0, 0, 1));
    EXPECT_NEAR(length(si.dpdu - face.s), 0, 1e-6);
    EXPECT_NEAR(length(si.dpdv - face.t), 0, 1e-6);
    hit.primId = 3;  // the sphere, hit at its +x point: dp/du = 2π r (0, 1, 0), dp/dv = π r (0, 0, -1)
    // (uv asked for: this scene has no textures, so by default a sphere's uv is not filled in)
    si = computeInteraction(view, Ray{Vec3f(4, 0, 5), Vec3f(-1, 0, 0), 10}, hit, true);
    EXPECT_NEAR(length(si.dpdu - Vec3f(0, 4 * kPi, 0)), 0, 1e-4);
    EXPECT_NEAR(length(si.dpdv - Vec3f(0, 0, -2 * kPi)), 0, 1e-4);
    EXPECT_NEAR(si.uv.x, 0, 1e-6);
    EXPECT_NEAR(si.uv.y, 0.5f, 1e-6);
}

}  // namespace
}  // namespace caustica
