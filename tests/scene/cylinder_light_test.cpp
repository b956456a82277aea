// cylinder_light_test.cpp — the cylinder as an area emitter: χ² of sampleLight's directions
// against the density implied by uniform area sampling (Mitsuba's Cylinder::sample_position:
// pdf 1 / (2π r length) by area), computed here independently from every front-facing crossing
// of the direction's ray, and per-sample agreement with pdfAreaLight and emittedRadiance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "accel/cylinder_reference.h"
#include "caustica/scene/light.h"
#include "caustica/util/rng.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

using test::addCylinder;

/// Solid-angle density of uniform area sampling seen from `ref` along unit `w`: the sum over the
/// ray's crossings of the lateral surface that face ref of d² / (cosθ · area), in double.
double directionDensity(const Cylinder& c, bool flip, Vec3f ref, Vec3f w) {
    const double area = 2 * M_PI * double(c.radius) * c.length;
    const double wd[3] = {w.x, w.y, w.z};
    const test::CylinderRoots roots(c, ref, w);
    double sum = 0;
    for (int i = 0; i < roots.count; ++i) {
        const double t = roots.t[i], h = roots.height(i);
        if (!(t > 0) || h < 0 || h > c.length) continue;
        double n[3];
        for (int k = 0; k < 3; ++k) n[k] = (roots.f[k] + roots.p[k] * t) / c.radius;
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

}  // namespace
}  // namespace caustica
