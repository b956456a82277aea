// Compatibility with Mitsuba 3 of the spot, directional and envmap emitters (compat_helpers.h:
// the scene matches its Mitsuba 3 reference, and the same statistics reject it with one
// parameter changed slightly).
#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

// Spot: Mitsuba 3's linear falloff between beam_width and cutoff_angle; 28 -> 30 degrees is seen.
TEST(MitsubaCompat, SpotEmitter) { checkPlugin("spot", {{"cutoff", "30"}}); }

// Directional lights by direction and by to_world; a 0.1 change in the direction is seen.
TEST(MitsubaCompat, DirectionalEmitter) {
    checkPlugin("directional", {{"direction", "0.6, -1, -0.3"}});
}

// Envmap: orientation, bilinear lookup, scale (pixels that see only the map's uniform ground
// rows are noise-free and must agree to 1e-5) and importance sampling; a rotation of 10 degrees
// (less than one texel of the 32-texel-wide map) is seen.
TEST(MitsubaCompat, EnvMapEmitter) { checkPlugin("envmap", {{"angle", "50"}}); }

}  // namespace
}  // namespace caustica::test
