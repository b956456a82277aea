// Compatibility with Mitsuba 3 of the thinlens and orthographic sensors and of film crop windows
// (compat_helpers.h: the scene matches its Mitsuba 3 reference, and the same statistics reject it
// with one parameter changed slightly). The ldrfilm has no Mitsuba 3 counterpart to compare with
// (tests/film/tonemap_test.cpp checks it).
#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

// Thin lens: defocus of near and far spheres; focus distance 4 -> 3.2 is seen.
TEST(MitsubaCompat, ThinLensSensor) { checkPlugin("thinlens", {{"focus", "3.2"}}, 256); }

// Orthographic: to_world's scale sets the extent; 1.6 -> 1.7 is seen.
TEST(MitsubaCompat, OrthographicSensor) { checkPlugin("orthographic", {{"scale", "1.7"}}); }

// Crop window of a 64x64 film; moving it by 2 pixels is seen.
TEST(MitsubaCompat, CropWindow) { checkPlugin("crop", {{"crop_x", "26"}}); }

}  // namespace
}  // namespace caustica::test
