// cylinder_light_test.cpp — the cylinder as an area emitter: χ² of sampleLight's directions
// against the density implied by uniform area sampling (Mitsuba's Cylinder::sample_position:
// pdf 1 / (2π r length) by area), computed here independently from every front-facing crossing
// of the direction's ray, and per-sample agreement with pdfAreaLight and emittedRadiance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "caustica/scene/light.h"
#include "caustica/util/rng.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

uint32_t addCylinder(Scene& scene, Vec3f base, Vec3f axis, Float radius, Float length,
                     bool flipNormals) {
    const uint32_t shapeId = uint32_t(scene.shapes.size());
    Shape shape;
    shape.type = ShapeType::Cylinder;
    shape.primOffset = uint32_t(scene.cylinders.size());
    shape.primCount = 1;
    shape.flipNormals = flipNormals;
    Cylinder c;
    c.base = base;
    c.axis = normalize(axis);
    c.xAxis = Frame(c.axis).s;
    c.radius = radius;
    c.length = length;
    c.shape = shapeId;
    scene.cylinders.push_back(c);
    scene.shapes.push_back(shape);
    return shapeId;
}

/// Solid-angle density of uniform area sampling seen from `ref` along unit `w`: the sum over the
/// ray's crossings of the lateral surface that face ref of d² / (cosθ · area), in double.
double directionDensity(const Cylinder& c, bool flip, Vec3f ref, Vec3f w) {
    const double area = 2 * M_PI * double(c.radius) * c.length;
    double f[3], d[3], ax[3] = {c.axis.x, c.axis.y, c.axis.z};
    const double fo[3] = {double(ref.x) - c.base.x, double(ref.y) - c.base.y,
                          double(ref.z) - c.base.z};
    const double wd[3] = {w.x, w.y, w.z};
    const double fa = fo[0] * ax[0] + fo[1] * ax[1] + fo[2] * ax[2];
    const double da = wd[0] * ax[0] + wd[1] * ax[1] + wd[2] * ax[2];
    for (int k = 0; k < 3; ++k) {
        f[k] = fo[k] - ax[k] * fa;
        d[k] = wd[k] - ax[k] * da;
    }
    const double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double b = 2 * (f[0] * d[0] + f[1] * d[1] + f[2] * d[2]);
    const double cc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - double(c.radius) * c.radius;
    const double disc = b * b - 4 * a * cc;
    if (!(a > 0) || disc < 0) return 0;
    double sum = 0;
    for (double t : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)}) {
        const double h = fa + da * t;
        if (!(t > 0) || h < 0 || h > c.length) continue;
        double n[3];
        for (int k = 0; k < 3; ++k) n[k] = (f[k] + d[k] * t) / c.radius;
        if (flip)
            for (double& v : n) v = -v;
        const double cosL = -(n[0] * wd[0] + n[1] * wd[1] + n[2] * wd[2]);
        if (cosL > 0) sum += t * t / (cosL * area);
    }
    return sum;
}

/// The emitting cylinder of the χ² tests.
const Vec3f kBase(0.2f, -0.3f, 0.1f), kAxis(0.3f, 1, 0.2f);
constexpr Float kRadius = 0.7f, kLength = 1.6f;

/// χ² over a cone of directions around `towards` that sees only the lateral surface, away from
/// the silhouette (where the solid-angle density has an integrable 1/cos singularity) and the
/// rims (where it jumps): there the density is smooth and the bins' quadrature converges.
/// Directions outside the cone and failed samples share the last bin.
void cylinderChi2(Vec3f ref, Vec3f towards, double thetaMax, bool flip, uint64_t seed) {
    Scene scene;
    const uint32_t shape = addCylinder(scene, kBase, kAxis, kRadius, kLength, flip);
    test::addAreaLight(scene, shape, Spectrum(2.f));
    finalizeLights(scene);
    const SceneView view = scene.view();
    ASSERT_NEAR(scene.lights[0].area, 2 * M_PI * kRadius * kLength, 1e-5);
    const Cylinder& c = scene.cylinders[0];
    int bad = 0;
    std::string firstBad;
    auto sample = [&](int i, Vec3f& w) {
        IndependentSampler rng(uint64_t(i), 0, seed);
        LightSample ls;
        const Float uSel = rng.get1D();
        if (!sampleLight(view, ref, uSel, rng.get2D(), ls)) return false;
        SurfaceInteraction si;
        si.p = ls.p;
        si.ng = si.ns = ls.n;
        si.shape = shape;
        const double pdf = pdfAreaLight(view, 0, ref, si);
        const Spectrum le = emittedRadiance(view, si, -ls.wi);
        // The sampled point lies on the surface, its normal is the (flipped) radial direction.
        const Vec3f q = ls.p - c.base;
        const Vec3f radial = q - c.axis * dot(q, c.axis);
        const bool ok = test::relClose(pdf, ls.pdf) && test::relClose(le.r, 2.0) &&
                        std::fabs(length(radial) - c.radius) < 1e-4f &&
                        dot(normalize(radial), ls.n) * (flip ? -1 : 1) > 0.9999f;
        if (!ok && bad++ == 0)
            firstBad = "sample " + std::to_string(i) + ": pdf " + std::to_string(ls.pdf) + " vs " +
                       std::to_string(pdf);
        w = ls.wi;
        return true;
    };
    test::SphereGrid grid;
    grid.frame = Frame(normalize(towards));
    grid.thetaMax = thetaMax;
    grid.nTheta = 16;
    grid.nPhi = 32;
    auto pdf = [&](Vec3f w) { return directionDensity(c, flip, ref, w); };
    const test::Chi2Result r = test::chi2Directions(grid, 1000000, sample, pdf);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(bad, 0) << firstBad;
}

TEST(CylinderLight, Chi2FromOutside) {
    const Vec3f ref(2.5f, 0.4f, -1.0f);
    const Vec3f middle = kBase + normalize(kAxis) * (kLength / 2);
    cylinderChi2(ref, middle - ref, 0.15, false, 21);  // the cylinder spans about ±0.28 rad
}

TEST(CylinderLight, Chi2FromInsideFlipped) {
    const Vec3f axis = normalize(kAxis);
    const Vec3f ref = kBase + axis * (kLength / 2) + Frame(axis).s * 0.2f;
    // Towards the wall, perpendicular to the axis; the rims are more than 0.8 rad away.
    cylinderChi2(ref, Frame(axis).t, 0.6, true, 22);
}

TEST(CylinderLight, OutwardCylinderSendsNothingInwards) {
    Scene scene;
    test::addAreaLight(scene, addCylinder(scene, {0, 0, 0}, {0, 0, 1}, 1, 2, false), Spectrum(1));
    finalizeLights(scene);
    const SceneView view = scene.view();
    int hits = 0;
    for (int i = 0; i < 1000; ++i) {
        IndependentSampler rng(uint64_t(i), 0, 5);
        LightSample ls;
        const Float uSel = rng.get1D();
        hits += sampleLight(view, Vec3f(0.1f, 0.2f, 1.0f), uSel, rng.get2D(), ls);
    }
    EXPECT_EQ(hits, 0);
}

}  // namespace
}  // namespace caustica
