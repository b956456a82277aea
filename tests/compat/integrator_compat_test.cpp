// integrator_compat_test.cpp — Mitsuba 3 compatibility of the integrators other than path (see
// compat_test.cpp for the method): the scene is rendered with its own integrator and compared
// with the Mitsuba 3 reference; one parameter changed slightly must be rejected.
#include "compat/compat_helpers.h"

namespace caustica::test {

// Mitsuba's direct with emitter_samples 2 and bsdf_samples 1: area, sphere and point lights, an
// environment, plastic and mirror spheres. Mitsuba counts a point light once per emitter sample,
// so emitter_samples 2 -> 3 changes the image and is detected.
TEST(MitsubaCompat, DirectIntegrator) {
    checkPlugin("direct", {{"emitter_samples", "3"}});
}

}  // namespace caustica::test
