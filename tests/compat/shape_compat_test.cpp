// shape_compat_test.cpp — shapes, instancing and spectra against Mitsuba 3 (scalar_rgb):
// each scene of tests/compat/scenes matches its reference, and a slightly wrong parameter must
// not (compat_helpers.h).
#include <gtest/gtest-spi.h>

#include "compat/compat_helpers.h"

namespace caustica::test {
namespace {

/// A second wrong parameter of a scene already checked by checkPlugin: the comparison must fail,
/// either statistically or by the exact checks on noise-free pixels (directly seen emitters),
/// which report their own failures; those are intercepted here as the expected outcome.
void expectNoMatch(const std::string& name, const std::map<std::string, std::string>& wrong) {
    testing::TestPartResultArray failures;
    ReferenceComparison bad;
    {
        testing::ScopedFakeTestPartResultReporter intercept(
            testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
        bad = compareScene(name, wrong, kWrongSppPerRun);
    }
    EXPECT_TRUE(failures.size() > 0 || !bad.passed())
        << name << " with a wrong parameter still matches: " << bad.describe();
}

TEST(ShapeCompat, Serialized) {
    checkPlugin("serialized", {{"face_normals", "true"}}, 128);  // faceted sphere
}

TEST(ShapeCompat, SerializedShapeIndex) {
    expectNoMatch("serialized", {{"index", "0"}});  // the sphere instead of the torus
}

TEST(ShapeCompat, Cylinder) {
    checkPlugin("cylinder", {{"radius", "0.45"}});
}

TEST(ShapeCompat, CylinderFlippedEmitter) {
    expectNoMatch("cylinder", {{"flip", "true"}});  // the lamp emits into itself
}

TEST(ShapeCompat, SphereUvFollowsARotatingToWorld) {
    checkPlugin("sphere_rotated", {{"angle", "60"}});  // checks and lobe turned by 10 degrees
}

TEST(ShapeCompat, Instance) {
    checkPlugin("instance", {{"dx", "1.2"}});
}

TEST(ShapeCompat, SpectrumLists) {
    checkPlugin("spectrum", {{"v600", "0.7"}});
}

TEST(ShapeCompat, ShapesWithFaceAndFlippedNormals) {
    checkPlugin("shapes", {{"obj_face", "true"}});
}

TEST(ShapeCompat, ShapesWrongNormals) {
    expectNoMatch("shapes", {{"ply_flip", "true"}});
    expectNoMatch("shapes", {{"disk_flip", "true"}});
}

}  // namespace
}  // namespace caustica::test
