// Compatibility with Mitsuba 3, one plugin at a time: small scenes (tests/compat/scenes) rendered
// by caustica and compared with Mitsuba 3 references (scalar_rgb, mean and variance of 16
// independent batches, scripts/make_compat_references.py) by the statistics of the end-to-end
// reference tests (tests/common/image_stats.h). Each scene is also rendered with one parameter
// changed slightly (through its <default>s), which the same statistics must reject: the tests
// can fail.
#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

// Mitsuba 3's default distribution (Beckmann) and named conductors (Au, Cu). A small roughness
// change, or GGX in place of Beckmann, is detected.
TEST(MitsubaCompat, RoughConductorBeckmann) {
    checkPlugin("roughconductor", {{"alpha", "0.23"}}, 256);
}

TEST(MitsubaCompat, RoughConductorGgxIsNotBeckmann) {
    const ReferenceComparison bad = compareScene("roughconductor", {{"distribution", "ggx"}}, 64);
    EXPECT_FALSE(bad.passed()) << bad.describe();
}

// Named measured conductors as Mitsuba's RGB eta/k; a neighbouring metal (Au for Cu) is detected.
TEST(MitsubaCompat, ConductorNamedMaterials) { checkPlugin("conductor", {{"material", "Au"}}); }

// Plastic (linear and nonlinear); int_ior 1.5 -> 1.6 is detected.
TEST(MitsubaCompat, Plastic) { checkPlugin("plastic", {{"int_ior", "1.6"}}, 256); }

// Thin dielectric pane; int_ior 1.5 -> 1.8 is detected.
TEST(MitsubaCompat, ThinDielectric) { checkPlugin("thindielectric", {{"int_ior", "1.8"}}); }

// Rough dielectric, Beckmann (default) and GGX, from both sides; alpha 0.2 -> 0.3 is detected.
TEST(MitsubaCompat, RoughDielectric) { checkPlugin("roughdielectric", {{"alpha", "0.3"}}, 128); }

}  // namespace
}  // namespace caustica::test
