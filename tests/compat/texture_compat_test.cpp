// Compatibility with Mitsuba 3 for textures and surface frames: bitmap and checkerboard textures
// as BSDF parameters, anisotropic roughness oriented by dp/du, bumpmap and normalmap (scenes in
// tests/compat/scenes, references by scripts/make_compat_references.py). Each scene must match
// its reference and must fail with one parameter changed (through its <default>s).
#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

// 8-bit sRGB PNG, bilinear, repeat, to_uv; nearest filtering is detected.
TEST(TextureCompat, Bitmap) { checkPlugin("bitmap", {{"filter", "nearest"}}); }

// Bitmap wrap mode: mirror instead of repeat is detected.
TEST(TextureCompat, BitmapWrapMode) {
    const ReferenceComparison bad = compareScene("bitmap", {{"wrap", "mirror"}});
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
    const ReferenceComparison bad = compareScene("normalmap", {{"raw", "false"}});
    EXPECT_FALSE(bad.passed()) << bad.describe();
}

}  // namespace
}  // namespace caustica::test
