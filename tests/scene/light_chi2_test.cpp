// χ² goodness-of-fit tests of light sampling against pdfAreaLight / pdfEnvironmentLight, with a
// per-sample check that the pdf sampleLight reports is the one the pdf functions give; one-sided
// area lights (sphere, cylinder) send nothing to a point behind them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "caustica/scene/light.h"
#include "caustica/util/rng.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

constexpr int kSamples = 1000000;

/// A surface interaction on light shape `shape` at `p` with front normal `n`.
SurfaceInteraction onLight(uint32_t shape, Vec3f p, Vec3f n) {
    SurfaceInteraction si;
    si.p = p;
    si.ng = si.ns = n;
    si.shape = shape;
    return si;
}

/// Draws light samples from `ref`, checking each against pdfAreaLight / pdfEnvironmentLight and
/// emittedRadiance, and returns the sampled direction (false = no sample).
struct LightSampler {
    const SceneView& view;
    Vec3f ref;
    uint64_t seed;
    int bad = 0;
    std::string firstBad;

    bool operator()(int i, LightSample& ls) {
        IndependentSampler rng(uint64_t(i), 0, seed);
        const Float uSel = rng.get1D();
        if (!sampleLight(view, ref, uSel, rng.get2D(), ls)) return false;
        const Light& light = view.lights[ls.light];
        Float pdf = 0;
        Spectrum le;
        if (light.type == LightType::Area) {
            const SurfaceInteraction si = onLight(light.shape, ls.p, ls.n);
            pdf = pdfAreaLight(view, ls.light, ref, si);
            le = emittedRadiance(view, si, -ls.wi);
        } else if (light.type == LightType::Constant) {
            pdf = pdfEnvironmentLight(view, ls.wi);
            le = environmentRadiance(view, ls.wi);
        } else {  // point: delta, pdf = selection probability
            pdf = Float(1) / Float(view.lights.size());
            le = light.radiance / lengthSquared(light.position - ref);
        }
        const bool ok = ls.delta == (light.type == LightType::Point) &&
                        test::relClose(pdf, ls.pdf) && test::relClose(le.r, ls.Le.r) &&
                        std::fabs(length(ls.wi) - 1) < 1e-5f &&
                        (light.type == LightType::Constant ||
                         test::relClose(length(ls.p - ref), ls.dist, 1e-5));
        if (!ok && bad++ == 0)
            firstBad = "sample " + std::to_string(i) + ": pdf " + std::to_string(ls.pdf) +
                       " vs " + std::to_string(pdf) + ", Le " + std::to_string(ls.Le.r) + " vs " +
                       std::to_string(le.r);
        return true;
    }
};

/// First intersection t > 0 of the ray ref + t w with a sphere (tangent rays count as hits).
double raySphere(Vec3f ref, Vec3f w, const Sphere& s) {
    const double ox = ref.x - s.center.x, oy = ref.y - s.center.y, oz = ref.z - s.center.z;
    const double b = ox * w.x + oy * w.y + oz * w.z;
    const double c = ox * ox + oy * oy + oz * oz - double(s.radius) * s.radius;
    const double disc = std::max(0.0, b * b - c);
    const double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
    return t0 > 0 ? t0 : t1;
}

/// Runs the χ² test of a sphere light seen from `ref` on `grid`.
void sphereChi2(const Scene& scene, Vec3f ref, const test::SphereGrid& grid, uint64_t seed) {
    const SceneView view = scene.view();
    const Sphere& sphere = scene.spheres[0];
    const bool flip = scene.shapes[0].flipNormals;
    LightSampler sampler{view, ref, seed, 0, {}};
    auto sample = [&](int i, Vec3f& w) {
        LightSample ls;
        if (!sampler(i, ls)) return false;
        w = ls.wi;
        return true;
    };
    auto pdf = [&](Vec3f w) {
        const Vec3f p = ref + w * Float(raySphere(ref, w, sphere));
        const Vec3f outward = normalize(p - sphere.center);
        return double(pdfAreaLight(view, 0, ref, onLight(0, p, flip ? -outward : outward)));
    };
    const test::Chi2Result r = test::chi2Directions(grid, kSamples, sample, pdf);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(sampler.bad, 0) << sampler.firstBad;
}

TEST(LightChi2, SphereFromOutside) {
    for (Float dist : {1.6f, 30.0f}) {  // a wide and a narrow cone
        Scene scene;
        const Vec3f center(0.3f, -0.2f, 0.5f);
        test::addAreaLight(scene, test::addSphere(scene, center, 1.0f), Spectrum(3.f));
        finalizeLights(scene);
        const Vec3f ref = center + normalize(Vec3f(1, 2, -0.5f)) * dist;
        test::SphereGrid grid;
        grid.frame = Frame(normalize(center - ref));
        grid.thetaMax = std::asin(1.0 / dist);  // exactly the visible cone
        grid.nTheta = 32;
        grid.nPhi = 64;
        sphereChi2(scene, ref, grid, 11 + uint64_t(dist));
    }
}

TEST(LightChi2, SphereFromInside) {
    Scene scene;  // flip_normals: the sphere emits inwards
    test::addAreaLight(scene, test::addSphere(scene, {0, 0, 0}, 2.0f, true), Spectrum(1.f));
    finalizeLights(scene);
    test::SphereGrid grid;
    grid.frame = Frame(normalize(Vec3f(0.2f, 0.5f, 1)));
    sphereChi2(scene, Vec3f(0.5f, 0.3f, -1.2f), grid, 12);
}

/// How many of 1000 light samples drawn from `ref` exist.
int lightSamplesDrawn(Scene& scene, Vec3f ref) {
    finalizeLights(scene);
    const SceneView view = scene.view();
    int hits = 0;
    for (int i = 0; i < 1000; ++i) {
        IndependentSampler rng(uint64_t(i), 0, 5);
        LightSample ls;
        const Float uSel = rng.get1D();
        hits += sampleLight(view, ref, uSel, rng.get2D(), ls);
    }
    return hits;
}

TEST(LightChi2, SphereFromInsideWithoutFlipEmitsNothingInwards) {
    Scene scene;
    test::addAreaLight(scene, test::addSphere(scene, {0, 0, 0}, 2.0f), Spectrum(1.f));
    EXPECT_EQ(lightSamplesDrawn(scene, Vec3f(0.1f, 0.2f, 0.3f)), 0);
}

TEST(CylinderLight, OutwardCylinderSendsNothingInwards) {
    Scene scene;
    test::addAreaLight(scene, test::addCylinder(scene, {0, 0, 0}, {0, 0, 1}, 1, 2, false),
                       Spectrum(1));
    EXPECT_EQ(lightSamplesDrawn(scene, Vec3f(0.1f, 0.2f, 1.0f)), 0);
}

TEST(LightChi2, Environment) {
    Scene scene;
    test::addSphere(scene, {0, 0, 0}, 1);
    test::addConstantLight(scene, Spectrum(0.25f, 0.5f, 1.0f));
    finalizeLights(scene);
    const SceneView view = scene.view();
    LightSampler sampler{view, Vec3f(0.2f, 0.1f, 0), 13, 0, {}};
    auto sample = [&](int i, Vec3f& w) {
        LightSample ls;
        if (!sampler(i, ls)) return false;
        w = ls.wi;
        return ls.dist == kInfinity;
    };
    auto pdf = [&](Vec3f w) { return double(pdfEnvironmentLight(view, w)); };
    test::SphereGrid grid;
    grid.frame = Frame(normalize(Vec3f(1, -1, 0.3f)));
    const test::Chi2Result r = test::chi2Directions(grid, kSamples, sample, pdf);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(sampler.bad, 0) << sampler.firstBad;
}

void meshChi2(const SceneView& view, const std::vector<test::RectMesh>& rects, Vec3f ref,
              double noSampleFraction) {
    constexpr int kCells = 16;
    const int nBins = 2 * kCells * kCells + 1;  // last: no sample / the point light
    auto cellOf = [&](Vec3f p) {
        for (size_t k = 0; k < rects.size(); ++k) {
            const test::RectMesh& r = rects[k];
            const Vec3f d = p - r.origin;
            const Vec3f n = normalize(cross(r.u, r.v));
            if (std::fabs(dot(d, n)) > 1e-4f) continue;
            const double s = dot(d, r.u) / lengthSquared(r.u), t = dot(d, r.v) / lengthSquared(r.v);
            const int i = std::clamp(int(s * kCells), 0, kCells - 1);
            const int j = std::clamp(int(t * kCells), 0, kCells - 1);
            return int(k) * kCells * kCells + i * kCells + j;
        }
        return -1;
    };
    LightSampler sampler{view, ref, 14 + uint64_t(ref.x), 0, {}};
    std::vector<double> obs(nBins, 0.0);
    int lost = 0;
    for (int i = 0; i < kSamples; ++i) {
        LightSample ls;
        if (!sampler(i, ls) || ls.light != 0) {
            obs.back() += 1;
            continue;
        }
        const int c = cellOf(ls.p);
        if (c < 0) ++lost;
        obs[c < 0 ? nBins - 1 : c] += 1;
    }
    // Expected counts by Simpson's rule (8 subintervals per cell; the integrand is smooth).
    std::vector<double> expected(nBins, 0.0);
    double total = 0;
    constexpr int kSub = 8;
    for (size_t k = 0; k < rects.size(); ++k) {
        const test::RectMesh& r = rects[k];
        const Vec3f n = normalize(cross(r.u, r.v));
        const double area = length(cross(r.u, r.v));
        for (int i = 0; i < kCells; ++i)
            for (int j = 0; j < kCells; ++j) {
                double sum = 0;
                for (int a = 0; a <= kSub; ++a)
                    for (int b = 0; b <= kSub; ++b) {
                        const Vec3f p = r.at((i + double(a) / kSub) / kCells,
                                             (j + double(b) / kSub) / kCells);
                        const Vec3f d = p - ref;
                        const double r2 = lengthSquared(d);
                        const double cosL = std::fabs(dot(d, n)) / std::sqrt(r2);
                        const double pdf = pdfAreaLight(view, 0, ref, onLight(0, p, n));
                        sum += test::simpsonWeight(a, kSub) * test::simpsonWeight(b, kSub) *
                               pdf * cosL / r2;
                    }
                const double e = sum / (9.0 * kSub * kSub) / (kCells * kCells) * area * kSamples;
                expected[k * kCells * kCells + i * kCells + j] = e;
                total += e;
            }
    }
    expected.back() = kSamples - total;
    EXPECT_EQ(lost, 0);
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(sampler.bad, 0) << sampler.firstBad;
    // The point light takes half the samples, back-facing parts of the mesh some more.
    EXPECT_NEAR(expected.back() / kSamples, noSampleFraction, 1e-4);
}

/// Area light on a mesh of two non-coplanar rectangles (8 triangles of unequal areas), seen from
/// a point in front of both and from one behind one of them. The histogram is over cells of the two
/// rectangles' (s, t) parameterisations; seen from `ref` each cell is a set of directions (no
/// self-occlusion here), and its expected count is N ∫ pdf dω = N ∫∫ pdf |cosθ_l| / r² dA.
TEST(LightChi2, MeshWithUnequalTriangles) {
    const std::vector<test::RectMesh> rects = {
        test::RectMesh({-1, -0.5f, 2}, {0, 1, 0}, {2, 0, 0}, 0.15f, 0.8f),    // faces -z
        test::RectMesh({1.5f, -1, -1}, {0, 0, 3}, {0, 2, 0}, 0.6f, 0.25f)};  // faces -x
    Scene scene;
    std::vector<Vec3f> pos;
    std::vector<Vec3u> tris;
    for (const test::RectMesh& r : rects) {
        const uint32_t base = uint32_t(pos.size());
        pos.insert(pos.end(), r.positions.begin(), r.positions.end());
        for (Vec3u t : r.triangles) tris.push_back({t.x + base, t.y + base, t.z + base});
    }
    test::addAreaLight(scene, test::addMesh(scene, pos, tris), Spectrum(2.f));
    test::addPointLight(scene, {0, 0, 5}, Spectrum(1.f));  // selection probability 1/2
    finalizeLights(scene);
    const SceneView view = scene.view();
    meshChi2(view, rects, Vec3f(0.5f, 0.2f, 0.4f), 0.5);  // both rectangles face it
    // Behind the -x rectangle (area 6 of 8): it is refused, the point light takes its half.
    meshChi2(view, rects, Vec3f(2.5f, 0.2f, 0.4f), 0.5 + 0.5 * 6 / 8);
}

/// A rectangle of two triangles, which finalizeLights samples as a parallelogram (Light::isQuad,
/// without the triangle CDF): the same directional density from points in front of it and none
/// from behind.
TEST(LightChi2, RectangleOfTwoTriangles) {
    test::RectMesh rect({-1, -0.5f, 2}, {0, 1, 0}, {2, 0, 0});  // faces -z
    rect.positions.resize(4);
    rect.triangles = {{0, 1, 2}, {2, 3, 0}};
    Scene scene;
    test::addAreaLight(scene, test::addMesh(scene, rect.positions, rect.triangles), Spectrum(2.f));
    test::addPointLight(scene, {0, 0, 5}, Spectrum(1.f));  // selection probability 1/2
    finalizeLights(scene);
    ASSERT_TRUE(scene.lights[0].isQuad);
    const SceneView view = scene.view();
    meshChi2(view, {rect}, Vec3f(0.3f, 0.2f, 0.4f), 0.5);
    meshChi2(view, {rect}, Vec3f(0.3f, 0.2f, 3.0f), 1.0);  // behind it
}

}  // namespace
}  // namespace caustica
