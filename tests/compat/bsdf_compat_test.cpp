// Compatibility with Mitsuba 3 of roughplastic, blendbsdf, mask, null, twosided and principled
// (scenes in tests/compat/scenes, references by scripts/make_compat_references.py; see
// compat_test.cpp).
// Each scene must match its reference and must not match with one parameter slightly changed.
#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

// Beckmann (Mitsuba's default) and GGX, nonlinear, water outside; alpha 0.1 -> 0.13 is detected.
TEST(MitsubaCompatBsdf, RoughPlastic) { checkPlugin("roughplastic", {{"alpha", "0.13"}}, 256); }

// A diffuse/rough-gold blend, and a twosided blend with a delta child (Mitsuba 3.9.1's mixture
// pdf and weight for delta samples); weight 0.3 -> 0.4 is detected.
TEST(MitsubaCompatBsdf, BlendBsdf) { checkPlugin("blendbsdf", {{"weight", "0.4"}}); }

// Masked cards (over a twosided diffuse and over a rough conductor); opacity 0.3 -> 0.4 is
// detected.
TEST(MitsubaCompatBsdf, Mask) { checkPlugin("mask", {{"opacity", "0.4"}}); }

// Null surfaces: crossings count as bounces, as Mitsuba's path integrator does; with one bounce
// more (max_depth 5 -> 6) the image differs.
TEST(MitsubaCompatBsdf, Null) { checkPlugin("null", {{"max_depth", "6"}}, 64); }

// A referenced twosided with different front and back; the back's roughness 0.2 -> 0.3 is
// detected.
TEST(MitsubaCompatBsdf, TwoSided) { checkPlugin("twosided", {{"alpha", "0.3"}}); }

// Principled: metallic, spec_tint, sheen, clearcoat on one sphere, transmission on the other;
// metallic 0.3 -> 0.4 is detected.
TEST(MitsubaCompatBsdf, Principled) { checkPlugin("principled", {{"metallic", "0.4"}}, 128); }

}  // namespace
}  // namespace caustica::test
