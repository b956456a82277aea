// camera_test.cpp — the projective cameras of scene/camera.h: the thin lens focuses every
// aperture sample of a film position on the pinhole ray's point at the focus distance and spreads
// origins uniformly over the aperture disk; the orthographic camera's rays are parallel and span
// Mitsuba's [-1, 1] x [-1/aspect, 1/aspect] scaled by to_world; a crop window's rays are the full
// image's rays at the offset position.
#include <gtest/gtest.h>

#include <cmath>

#include "caustica/scene/camera.h"
#include "caustica/util/rng.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

Transform lookAtish() {
    Matrix4 m;  // a rotation about y by 30 degrees and a translation
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    m.m[0][0] = Float(c), m.m[0][2] = Float(s), m.m[2][0] = Float(-s), m.m[2][2] = Float(c);
    m.m[0][3] = 1, m.m[1][3] = 2, m.m[2][3] = -3;
    return Transform::fromMatrix(m);
}

Camera perspective(CameraType type = CameraType::Perspective) {
    Camera cam;
    cam.type = type;
    cam.worldFromCamera = lookAtish();
    cam.width = 40;
    cam.height = 30;
    cam.tanHalfX = 0.5f;
    cam.tanHalfY = 0.375f;
    return cam;
}

/// Point of a ray at parameter t.
Vec3f at(const Ray& r, Float t) { return r.o + r.d * t; }

TEST(ThinLens, FocusesOnThePinholePoint) {
    Camera pin = perspective(), lens = perspective(CameraType::ThinLens);
    lens.apertureRadius = 0.2f;
    lens.focusDistance = 5;
    const Vec3f camZ = normalize(lens.worldFromCamera.applyVector(Vec3f(0, 0, 1)));
    const Vec3f eye = lens.worldFromCamera.applyPoint(Vec3f(0));
    for (Vec2f film : {Vec2f(3.5f, 7.25f), Vec2f(20, 15), Vec2f(39.9f, 0.1f)}) {
        const Ray p = generateCameraRay(pin, film);
        // The pinhole ray's point on the plane z_cam = focus distance.
        const Float tp = (5 - dot(p.o - eye, camZ)) / dot(p.d, camZ);
        const Vec3f focus = at(p, tp);
        for (int i = 0; i < 64; ++i) {
            IndependentSampler rng(uint64_t(i), 0, 3);
            const Ray r = generateCameraRay(lens, film, rng.get2D());
            EXPECT_NEAR(length(r.d), 1, 1e-5);
            const Float t = (5 - dot(r.o - eye, camZ)) / dot(r.d, camZ);
            EXPECT_LT(length(at(r, t) - focus), 2e-5f * 5) << film.x << " " << film.y;
            // The origin lies on the near plane, its aperture point within the radius.
            const Vec3f back = r.o - r.d * (lens.nearClip / dot(r.d, camZ));
            EXPECT_LE(length(back - eye), 0.2f + 1e-5f);
        }
    }
}

TEST(ThinLens, ClosedApertureIsThePinhole) {
    Camera pin = perspective(), lens = perspective(CameraType::ThinLens);
    lens.apertureRadius = 0;
    lens.focusDistance = 3;
    EXPECT_FALSE(cameraNeedsLensSample(lens));
    const Ray a = generateCameraRay(pin, Vec2f(7, 9)), b = generateCameraRay(lens, Vec2f(7, 9), Vec2f(0.9f, 0.1f));
    EXPECT_NEAR(length(a.o - b.o), 0, 1e-6);
    EXPECT_NEAR(length(a.d - b.d), 0, 1e-6);
}

/// Aperture points are uniform over the disk: χ² over rings of equal area and quadrants.
TEST(ThinLens, ApertureIsUniform) {
    Camera lens = perspective(CameraType::ThinLens);
    lens.worldFromCamera = Transform();
    lens.apertureRadius = 0.5f;
    lens.focusDistance = 2;
    ASSERT_TRUE(cameraNeedsLensSample(lens));
    constexpr int kRings = 8, kSectors = 16, kN = 200000;
    std::vector<double> obs(kRings * kSectors, 0.0), expected(obs.size(), double(kN) / obs.size());
    for (int i = 0; i < kN; ++i) {
        IndependentSampler rng(uint64_t(i), 0, 9);
        const Ray r = generateCameraRay(lens, Vec2f(20, 15), rng.get2D());
        const Vec3f back = r.o - r.d * (lens.nearClip / r.d.z);  // the aperture point (z = 0)
        const double rr = (back.x * back.x + back.y * back.y) / 0.25;
        double phi = std::atan2(back.y, back.x);
        if (phi < 0) phi += 2 * M_PI;
        const int ring = std::min(int(rr * kRings), kRings - 1);
        const int sector = std::min(int(phi / (2 * M_PI) * kSectors), kSectors - 1);
        obs[ring * kSectors + sector] += 1;
    }
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
}

TEST(Orthographic, ParallelRaysOverTheScaledExtent) {
    Camera cam;
    cam.type = CameraType::Orthographic;
    cam.width = 40;
    cam.height = 20;
    cam.tanHalfX = 1;
    cam.tanHalfY = 0.5f;
    Matrix4 m;  // scale 3 in x and y, then translate
    m.m[0][0] = 3, m.m[1][1] = 3, m.m[0][3] = 1, m.m[1][3] = 2, m.m[2][3] = -1;
    cam.worldFromCamera = Transform::fromMatrix(m);
    cam.nearClip = 0.5f;
    cam.farClip = 10;
    // Film (0, 0) is camera (+1, +1/aspect) (Mitsuba flips both axes); the centre is the axis.
    const Ray corner = generateCameraRay(cam, Vec2f(0, 0));
    EXPECT_NEAR(length(corner.o - Vec3f(1 + 3, 2 + 1.5f, -1 + 0.5f)), 0, 1e-5);
    const Ray centre = generateCameraRay(cam, Vec2f(20, 10));
    EXPECT_NEAR(length(centre.o - Vec3f(1, 2, -0.5f)), 0, 1e-5);
    const Ray other = generateCameraRay(cam, Vec2f(40, 20));
    EXPECT_NEAR(length(other.o - Vec3f(1 - 3, 2 - 1.5f, -0.5f)), 0, 1e-5);
    for (const Ray& r : {corner, centre, other}) {
        EXPECT_NEAR(length(r.d - Vec3f(0, 0, 1)), 0, 1e-6);
        EXPECT_FLOAT_EQ(r.tMax, 9.5f);
    }
}

TEST(CropWindow, RaysAreTheFullImagesAtTheOffset) {
    for (CameraType type : {CameraType::Perspective, CameraType::Orthographic, CameraType::ThinLens}) {
        Camera full = perspective(type);
        full.apertureRadius = 0.1f;
        full.focusDistance = 4;
        Camera crop = full;
        crop.cropX = 13;
        crop.cropY = 4;
        for (Vec2f p : {Vec2f(0.25f, 0.5f), Vec2f(9.75f, 11.5f)}) {
            const Ray a = generateCameraRay(crop, p, Vec2f(0.3f, 0.7f));
            const Ray b = generateCameraRay(full, Vec2f(p.x + 13, p.y + 4), Vec2f(0.3f, 0.7f));
            EXPECT_NEAR(length(a.o - b.o), 0, 1e-5);
            EXPECT_NEAR(length(a.d - b.d), 0, 1e-6);
        }
    }
}

}  // namespace
}  // namespace caustica
