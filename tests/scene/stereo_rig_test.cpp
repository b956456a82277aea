// stereo_rig_test.cpp — the stereo rig (scene/stereo_rig.h, camera.h): eye positions (left eye on
// the viewer's left), off-axis frusta that meet at the convergence plane, parallel and toe-in
// projections against hand-computed ones, each eye equal to its mono eyeCamera, and refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "caustica/scene/stereo_rig.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

constexpr int kW = 40, kH = 30;
constexpr Float kTan = 0.5f;  // tan of half the horizontal field of view

/// A camera at (0, 0, 3) looking at the origin, up +y: the viewer's right is world +x.
Camera camera(CameraType type = CameraType::Perspective) {
    Camera c;
    c.type = type;
    c.worldFromCamera = lookAt(Vec3f(0, 0, 3), Vec3f(0, 0, 0), Vec3f(0, 1, 0));
    c.width = kW;
    c.height = kH;
    c.tanHalfX = kTan;
    c.tanHalfY = kTan * Float(kH) / Float(kW);
    return c;
}

Camera rig(StereoMode mode, Float interocular = 0.2f, Float convergence = 2.0f) {
    Camera c = camera();
    EXPECT_EQ(makeStereoRig(c, kW, StereoSettings{mode, interocular, convergence}), 2 * kW);
    return c;
}

/// Where a ray meets the plane z = z0 (world).
Vec3f onPlaneZ(const Ray& r, Float z0) { return r.o + r.d * ((z0 - r.o.z) / r.d.z); }

/// Film x (rig film, both eyes) of the hand-computed pinhole projection of world point p for an
/// eye at world x = e whose axis is parallel to -z: u = 1/2 + (p.x - e) / (depth 2 tan).
Float parallelFilmX(Vec3f p, Float e, int eye, Float shift = 0) {
    const Float depth = 3 - p.z;
    const Float u = 0.5f + ((p.x - e) / depth + shift) / (2 * kTan);
    return u * kW + Float(eye * kW);
}

TEST(StereoRig, LeftEyeSitsOnTheViewersLeft) {
    for (StereoMode mode : {StereoMode::OffAxis, StereoMode::Parallel, StereoMode::ToeIn}) {
        const Camera c = rig(mode);
        const Vec3f left = cameraEyePosition(c, 1.0f), right = cameraEyePosition(c, Float(kW) + 1);
        EXPECT_NEAR(left.x, -0.1f, 1e-6f);  // viewer's right is +x: the left eye at -interocular/2
        EXPECT_NEAR(right.x, 0.1f, 1e-6f);
        EXPECT_NEAR(left.z, 3.0f, 1e-6f);
        EXPECT_EQ(cameraEyeOf(c, Float(kW) - 0.01f), 0);
        EXPECT_EQ(cameraEyeOf(c, Float(kW)), 1);
    }
}

TEST(StereoRig, OffAxisFrustaMeetAtTheConvergencePlane) {
    const Camera c = rig(StereoMode::OffAxis, 0.2f, 2.0f), mono = camera();
    for (Float y : {0.5f, 7.25f, 29.5f})
        for (Float x : {0.0f, 3.5f, 20.0f, 39.75f}) {
            const Vec3f l = onPlaneZ(generateCameraRay(c, Vec2f(x, y)), 1.0f);  // z = 3 - convergence
            const Vec3f r = onPlaneZ(generateCameraRay(c, Vec2f(x + kW, y)), 1.0f);
            const Vec3f m = onPlaneZ(generateCameraRay(mono, Vec2f(x, y)), 1.0f);
            EXPECT_NEAR(l.x, r.x, 1e-5f) << x << "," << y;
            EXPECT_NEAR(l.y, r.y, 1e-5f);
            EXPECT_NEAR(l.x, m.x, 1e-5f);  // and where the centre camera sees that pixel
            EXPECT_NEAR(l.y, m.y, 1e-5f);
        }
    // Off the plane the eyes disagree: halfway to it the centre pixels' rays are half the
    // interocular distance apart (left eye's on the left).
    const Vec3f l = onPlaneZ(generateCameraRay(c, Vec2f(20, 15)), 2.0f);
    const Vec3f r = onPlaneZ(generateCameraRay(c, Vec2f(20 + kW, 15)), 2.0f);
    EXPECT_NEAR(r.x - l.x, 0.1f, 1e-5f);
}

TEST(StereoRig, OffAxisAndParallelProjectionsByHand) {
    const Vec3f points[] = {Vec3f(0.3f, 0.1f, 0.5f), Vec3f(-0.7f, -0.2f, -1.0f), Vec3f(0.05f, 0.3f, 1.6f)};
    for (StereoMode mode : {StereoMode::Parallel, StereoMode::OffAxis}) {
        const Camera c = rig(mode, 0.2f, 2.0f);
        for (const Vec3f& p : points)
            for (int eye = 0; eye < 2; ++eye) {
                const Float e = eye == 0 ? -0.1f : 0.1f;
                // Off-axis: the frustum shifted by e / C (image plane units, towards the centre).
                const Float shift = mode == StereoMode::OffAxis ? e / 2.0f : 0.0f;
                const Float fx = parallelFilmX(p, e, eye, shift);
                const Float fy = (0.5f - p.y / (3 - p.z) / (2 * c.tanHalfY)) * kH;
                const Ray ray = generateCameraRay(c, Vec2f(fx, fy));
                const Vec3f toP = normalize(p - Vec3f(e, 0, 3));
                EXPECT_NEAR(ray.d.x, toP.x, 2e-5f) << int(mode) << " eye " << eye;
                EXPECT_NEAR(ray.d.y, toP.y, 2e-5f);
                EXPECT_NEAR(ray.d.z, toP.z, 2e-5f);
            }
    }
}

TEST(StereoRig, ToeInEyesLookAtTheConvergencePointAndProjectByHand) {
    const Float h = 0.1f, C = 2.0f;
    const Camera c = rig(StereoMode::ToeIn, 2 * h, C);
    for (int eye = 0; eye < 2; ++eye) {
        const Float e = eye == 0 ? -h : h;
        // The centre pixel's ray goes through the convergence point (0, 0, 3 - C).
        const Ray centre = generateCameraRay(c, Vec2f(kW / 2 + eye * kW, kH / 2));
        const Vec3f want = normalize(Vec3f(-e, 0, -C));
        EXPECT_NEAR(centre.d.x, want.x, 1e-6f);
        EXPECT_NEAR(centre.d.z, want.z, 1e-6f);
        // Another pixel: the eye's axis turned by atan(-e / C) about y, the pixel's offset from it
        // atan(tan * (2u - 1)) (image x right = world +x for this camera).
        const Float u = 0.8f;
        const Float angle = std::atan2(-e, C) + std::atan(kTan * (2 * u - 1));
        const Ray r = generateCameraRay(c, Vec2f(u * kW + Float(eye * kW), kH / 2));
        EXPECT_NEAR(r.d.x, std::sin(angle), 1e-5f);
        EXPECT_NEAR(r.d.z, -std::cos(angle), 1e-5f);
        EXPECT_NEAR(r.d.y, 0.0f, 1e-6f);
    }
}

TEST(StereoRig, EachEyeIsItsMonoEyeCamera) {
    for (StereoMode mode : {StereoMode::OffAxis, StereoMode::Parallel, StereoMode::ToeIn})
        for (CameraType type : {CameraType::Perspective, CameraType::ThinLens}) {
            Camera c = camera(type);
            c.apertureRadius = 0.05f;
            c.focusDistance = 2.5f;
            makeStereoRig(c, kW, StereoSettings{mode, 0.1f, 1.5f});
            for (int eye = 0; eye < 2; ++eye) {
                const Camera mono = eyeCamera(c, eye);
                for (Vec2f p : {Vec2f(0.25f, 0.5f), Vec2f(17.5f, 9.0f), Vec2f(39.9f, 29.9f)}) {
                    const Ray a = generateCameraRay(c, Vec2f(p.x + Float(eye * kW), p.y), Vec2f(0.3f, 0.8f));
                    const Ray b = generateCameraRay(mono, p, Vec2f(0.3f, 0.8f));
                    EXPECT_EQ(a.o.x, b.o.x);
                    EXPECT_EQ(a.o.z, b.o.z);
                    EXPECT_EQ(a.d.x, b.d.x);
                    EXPECT_EQ(a.d.y, b.d.y);
                    EXPECT_EQ(a.d.z, b.d.z);
                    EXPECT_EQ(a.tMax, b.tMax);
                }
            }
        }
}

TEST(StereoRig, RefusesBadSettingsWithOneLine) {
    Camera c = camera();
    auto refuses = [&](StereoSettings s, const char* what) {
        Camera copy = c;
        try {
            makeStereoRig(copy, kW, s);
            ADD_FAILURE() << "accepted " << what;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    };
    refuses({StereoMode::OffAxis, -0.065f, 1.95f}, "--interocular");
    refuses({StereoMode::OffAxis, 0.0f, 1.95f}, "--interocular");
    refuses({StereoMode::OffAxis, 0.065f, 0.0f}, "--convergence");
    refuses({StereoMode::ToeIn, 0.065f, -2.0f}, "--convergence");
    refuses({StereoMode::Parallel, NAN, 1.95f}, "--interocular");
    c = camera(CameraType::Orthographic);
    refuses({StereoMode::Parallel, 0.065f, 1.95f}, "orthographic");
    EXPECT_THROW(parseStereoMode("sideways"), Error);
    EXPECT_EQ(parseStereoMode("toe-in"), StereoMode::ToeIn);
    EXPECT_STREQ(stereoModeName(parseStereoMode("off-axis")), "off-axis");
}

}  // namespace
}  // namespace caustica
