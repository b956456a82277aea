// Compatibility with Mitsuba 3 for textures and surface frames: bitmap and checkerboard textures
// as BSDF parameters (principled weights, conductor eta/k, nested checkerboards), a spot light's
// texture, anisotropic roughness oriented by dp/du, bumpmap and normalmap (scenes in
// tests/compat/scenes, references by scripts/make_compat_references.py). Each scene must match
// its reference and must fail with one parameter changed (through its <default>s).
#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

// 8-bit sRGB PNG, bilinear, repeat, to_uv; nearest filtering is detected.
TEST(TextureCompat, Bitmap) { checkPlugin("bitmap", {{"filter", "nearest"}}); }

// Bitmap wrap mode: mirror instead of repeat is detected.
TEST(TextureCompat, BitmapWrapMode) {
    const ReferenceComparison bad = compareScene("bitmap", {{"wrap", "mirror"}}, kWrongSppPerRun);
    EXPECT_FALSE(bad.passed()) << bad.describe();
}

// Checkerboard (diffuse reflectance, roughconductor specular_reflectance); a changed color0 is
// detected.
TEST(TextureCompat, Checkerboard) { checkPlugin("checkerboard", {{"color0", "0.8, 0.3, 0.2"}}); }

// Anisotropic GGX roughconductor on a sphere and a rotated quad: alpha_u and alpha_v swapped (the
// lobe turned by 90° in the dp/du frame) is detected.
TEST(TextureCompat, AnisotropicRoughConductor) {
    checkPlugin("roughconductor_aniso", {{"alpha_u", "0.4"}, {"alpha_v", "0.05"}});
}

// Bump mapping (diffuse quad, twosided rough conductor sphere); scale 0.15 -> 0.2 is detected.
TEST(TextureCompat, BumpMap) { checkPlugin("bumpmap", {{"scale", "0.2"}}); }

// Normal mapping (diffuse quad, plastic sphere) with Mitsuba's shadowing term for perturbed
// normals; leaving the term out is detected.
TEST(TextureCompat, NormalMap) { checkPlugin("normalmap", {{"shadowing", "false"}}); }

// An sRGB-decoded (not raw) normal map is detected too.
TEST(TextureCompat, NormalMapRaw) {
    const ReferenceComparison bad = compareScene("normalmap", {{"raw", "false"}}, kWrongSppPerRun);
    EXPECT_FALSE(bad.passed()) << bad.describe();
}

// Principled with every textured weight (checkerboards and a bitmap); the spec_trans
// checkerboard's color0 0.9 -> 0.7 is detected.
TEST(TextureCompat, PrincipledTextures) { checkPlugin("tex_principled", {{"trans0", "0.7"}}); }

// Conductor and roughconductor with textured eta and k; a changed eta colour is detected.
TEST(TextureCompat, ConductorEtaK) { checkPlugin("tex_conductor", {{"eta0", "0.3, 0.8, 0.6"}}); }

// Spot light with a projected bitmap; the texture turned by 90° in uv is detected.
TEST(TextureCompat, SpotTexture) { checkPlugin("tex_spot", {{"angle", "90"}}); }

// Checkerboards nested in checkerboards (eval and eval_1); a changed inner color0 is detected.
TEST(TextureCompat, NestedCheckerboard) {
    checkPlugin("tex_checkerboard_nested", {{"inner0", "0.6, 0.4, 0.1"}});
}

}  // namespace
}  // namespace caustica::test
