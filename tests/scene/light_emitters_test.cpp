// light_emitters_test.cpp — the spot, directional and envmap emitters (light_delta.h,
// light_envmap.h): a χ² test of envmap sampling against its pdf in the map's uv square (where the
// pdf is piecewise constant and the expected counts exact; a grid over directions cuts the
// patches' discontinuities, which Simpson quadrature cannot integrate to the χ² test's
// accuracy), per-sample agreement of the sampled pdf and radiance with pdfEnvironmentLight and
// environmentRadiance, the pdf's integral over the sphere of directions (normalisation and the
// sinθ Jacobian), Mitsuba 3's map orientation and interpolation (values printed by
// Mitsuba 3.9.1's envmap.eval for the same 4x3 map), and the exact radiance of the delta emitters
// (spot falloff, directional irradiance), which have no sampling density to test.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "caustica/scene/light.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

using test::addEnvMap;

constexpr int kSamples = 1000000;

/// A 12x7 test map: a gradient, a bright spot, a black band (zero probability) and a bright texel
/// on the seam column.
std::vector<Spectrum> testTexels(int w, int h) {
    std::vector<Spectrum> t;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Spectrum v(0.2f + 0.1f * x, 0.5f, 0.3f + 0.2f * y);
            if (x >= 3 && x <= 5) v = Spectrum(0.0f);
            if (x == 8 && y == 2) v = Spectrum(30, 20, 10);
            if (x == w - 1 && y == 4) v = Spectrum(8.0f);
            t.push_back(v);
        }
    return t;
}

Transform rotation() {
    Matrix4 m;  // a rotation about (1, 2, 3) by 50 degrees (Rodrigues)
    const Vec3f a = normalize(Vec3f(1, 2, 3));
    const double th = 50 * M_PI / 180, c = std::cos(th), s = std::sin(th);
    const double k[3] = {a.x, a.y, a.z};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double v = (1 - c) * k[i] * k[j] + (i == j ? c : 0);
            if (i != j) {
                const int l = 3 - i - j;
                const double sign = ((j - i + 3) % 3 == 1) ? -1 : 1;
                v += sign * s * k[l];
            }
            m.m[i][j] = Float(v);
        }
    return Transform::fromMatrix(m);
}

Scene envScene(bool withPoint) {
    Scene scene;
    test::addSphere(scene, {0, 0, 0}, 1);
    addEnvMap(scene, 12, 7, testTexels(12, 7), rotation());
    if (withPoint) test::addPointLight(scene, {0, 3, 0}, Spectrum(1.0f));
    finalizeLights(scene);
    return scene;
}

/// Samples the environment through sampleLight, checking each sample's pdf and radiance against
/// pdfEnvironmentLight / environmentRadiance. Returns false for "no sample" or another light.
struct EnvSampler {
    const SceneView& view;
    int bad = 0;
    std::string firstBad;
    bool operator()(int i, Vec3f& w) {
        IndependentSampler rng(uint64_t(i), 0, 21);
        const Float uSel = rng.get1D();
        LightSample ls;
        if (!sampleLight(view, Vec3f(0.1f, 0.2f, 0.3f), uSel, rng.get2D(), ls)) return false;
        if (ls.light != uint32_t(view.environmentLight)) return false;
        const Float pdf = pdfEnvironmentLight(view, ls.wi);
        const Spectrum le = environmentRadiance(view, ls.wi);
        const bool ok = !ls.delta && ls.dist == kInfinity && test::relClose(pdf, ls.pdf, 1e-3) &&
                        test::relClose(le.r, ls.Le.r, 1e-3) && test::relClose(le.b, ls.Le.b, 1e-3);
        if (!ok && bad++ == 0)
            firstBad = "sample " + std::to_string(i) + ": pdf " + std::to_string(ls.pdf) + " vs " +
                       std::to_string(pdf) + ", Le " + std::to_string(ls.Le.r) + " vs " +
                       std::to_string(le.r);
        w = ls.wi;
        return true;
    }
};

/// χ² in the map's own uv square: cells are quarters of the bilinear patches, where the density
/// p(u, v) = pdf_ω · 2π² sinθ is constant, so the expected counts are exact.
TEST(EnvMapChi2, UvSquare) {
    const Scene scene = envScene(true);
    const SceneView view = scene.view();
    const Light& l = scene.lights[0];
    const int W = int(l.texWidth), H = int(l.texHeight), sub = 2;
    const int nu = W * sub, nv = (H - 1) * sub;
    std::vector<double> obs(size_t(nu) * nv + 1, 0.0), expected(obs.size(), 0.0);
    EnvSampler sampler{view, 0, {}};
    for (int i = 0; i < kSamples; ++i) {
        Vec3f w;
        if (!sampler(i, w)) {
            obs.back() += 1;
            continue;
        }
        const Vec3f local = normalize(applyRows(l.localFromWorld, w));
        const Vec2f g = envmap_detail::uvToGrid(l, envmap_detail::directionToUv(local));
        const int cu = std::min(int(g.x * sub), nu - 1), cv = std::min(int(g.y * sub), nv - 1);
        obs[size_t(cv) * nu + cu] += 1;
    }
    double total = 0;
    for (int cv = 0; cv < nv; ++cv)
        for (int cu = 0; cu < nu; ++cu) {
            // Cell centre in grid coordinates -> uv -> direction; density per unit grid area.
            const double s = (cu + 0.5) / sub, t = (cv + 0.5) / sub;
            double u = (s + 0.5) / W;
            if (u >= 1) u -= 1;
            const double v = t / (H - 1);
            Float sinTheta;
            const Vec3f local = envmap_detail::uvToDirection(Vec2f(Float(u), Float(v)), sinTheta);
            const Vec3f w = normalize(applyRows(l.worldFromLocal, local));
            const double pUv = double(pdfEnvironmentLight(view, w)) * 2 * M_PI * M_PI * sinTheta;
            const double e = pUv / (double(W) * (H - 1)) / (sub * sub) * kSamples;
            expected[size_t(cv) * nu + cu] = e;
            total += e;
        }
    expected.back() = kSamples - total;
    EXPECT_NEAR(total / kSamples, 0.5, 1e-4);  // the point light takes the other half
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
    EXPECT_EQ(sampler.bad, 0) << sampler.firstBad;
}

/// ∫ pdf dω = 1 over the sphere (midpoint rule in (θ, φ), fine enough for the patches).
TEST(EnvMap, PdfIntegratesToOne) {
    const Scene scene = envScene(false);
    const SceneView view = scene.view();
    const int nt = 700, np = 1400;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
        const double theta = (i + 0.5) * M_PI / nt;
        for (int j = 0; j < np; ++j) {
            const double phi = (j + 0.5) * 2 * M_PI / np;
            const Vec3f w(Float(std::sin(theta) * std::cos(phi)), Float(std::sin(theta) * std::sin(phi)),
                          Float(std::cos(theta)));
            sum += pdfEnvironmentLight(view, w) * std::sin(theta);
        }
    }
    EXPECT_NEAR(sum * (M_PI / nt) * (2 * M_PI / np), 1.0, 2e-3);
}

/// A black map has nothing to sample; a black band has zero density and zero radiance.
TEST(EnvMap, BlackRegionsAreNeverSampled) {
    Scene scene;
    test::addSphere(scene, {0, 0, 0}, 1);
    addEnvMap(scene, 4, 3, std::vector<Spectrum>(12, Spectrum(0.0f)));
    finalizeLights(scene);
    LightSample ls;
    EXPECT_FALSE(sampleLight(scene.view(), Vec3f(0), 0.3f, Vec2f(0.4f, 0.6f), ls));
    EXPECT_EQ(pdfEnvironmentLight(scene.view(), Vec3f(0, 0, 1)), 0.0f);
}

/// Mitsuba 3.9.1's orientation and interpolation: for the 4x3 map with texel (x, y) = (x + 1,
/// 10 (y + 1), 0), `envmap.eval` gives these values along d = (sinφ sinθ, cosθ, −cosφ sinθ)
/// with u = φ/2π, v = θ/π (tests/compat/envmap.xml checks the same against renders).
TEST(EnvMap, MatchesMitsubaOrientation) {
    std::vector<Spectrum> t;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) t.push_back(Spectrum(Float(x + 1), Float(10 * (y + 1)), 0));
    Scene scene;
    addEnvMap(scene, 4, 3, t);
    finalizeLights(scene);
    const SceneView view = scene.view();
    struct Case { double v, u; float r, g; };
    const Case cases[] = {{0.0, 0.5, 2.5f, 10}, {0.5, 0.0, 2.5f, 20}, {0.5, 0.125, 1, 20},
                          {0.5, 0.25, 1.5f, 20}, {0.5, 0.5, 2.5f, 20}, {1.0, 0.125, 1, 30},
                          {0.25, 0.625, 3, 15}};
    for (const Case& c : cases) {
        const double th = c.v * M_PI, ph = c.u * 2 * M_PI;
        const Vec3f d(Float(std::sin(ph) * std::sin(th)), Float(std::cos(th)),
                      Float(-std::cos(ph) * std::sin(th)));
        const Spectrum le = environmentRadiance(view, d);
        EXPECT_NEAR(le.r, c.r, 1e-4) << "v " << c.v << " u " << c.u;
        EXPECT_NEAR(le.g, c.g, 1e-3) << "v " << c.v << " u " << c.u;
    }
}

/// Mitsuba 3's spot: full intensity inside beam_width, linear in the angle to 0 at cutoff_angle.
TEST(SpotLight, FalloffAndRadiance) {
    Scene scene;
    Light l;
    l.type = LightType::Spot;
    l.radiance = Spectrum(4, 2, 1);
    l.position = Vec3f(0, 2, 0);
    const double cutoff = 30 * M_PI / 180, beam = 20 * M_PI / 180;
    l.cutoff = Float(cutoff);
    l.cosCutoff = Float(std::cos(cutoff));
    l.cosBeam = Float(std::cos(beam));
    l.invTransition = Float(1 / (cutoff - beam));
    // to_world: +z (the axis) points down -y.
    l.localFromWorld[0] = Vec3f(1, 0, 0);
    l.localFromWorld[1] = Vec3f(0, 0, 1);
    l.localFromWorld[2] = Vec3f(0, -1, 0);
    scene.lights.push_back(l);
    finalizeLights(scene);
    const SceneView view = scene.view();
    for (double deg : {0.0, 10.0, 19.9, 22.0, 25.0, 29.0, 31.0}) {
        const double a = deg * M_PI / 180;
        const Vec3f ref(Float(2 * std::tan(a)), 0, 0);  // on the floor y = 0, 2 below the light
        LightSample ls;
        const bool ok = sampleLight(view, ref, 0.5f, Vec2f(0.5f, 0.5f), ls);
        const double falloff = deg <= 20 ? 1 : std::max(0.0, (30 - deg) / 10);
        if (falloff == 0) {
            EXPECT_FALSE(ok) << deg;
            continue;
        }
        ASSERT_TRUE(ok) << deg;
        const double d2 = 4 + double(ref.x) * ref.x;
        EXPECT_TRUE(ls.delta);
        EXPECT_EQ(ls.pdf, 1.0f);
        EXPECT_NEAR(ls.Le.r, 4 * falloff / d2, 1e-4) << deg;
        EXPECT_NEAR(ls.Le.g, 2 * falloff / d2, 1e-4) << deg;
        EXPECT_NEAR(ls.dist, std::sqrt(d2), 1e-5);
        EXPECT_NEAR(length(ls.wi - normalize(l.position - ref)), 0, 1e-6);
    }
}

/// Mitsuba 3's directional: irradiance along `direction`, from a point two scene radii away, an
/// unbounded shadow ray; selected uniformly with the other lights.
TEST(DirectionalLight, Sample) {
    Scene scene;
    test::addSphere(scene, {1, 0, 0}, 2);
    Light l;
    l.type = LightType::Directional;
    l.radiance = Spectrum(3, 2, 1);
    l.direction = normalize(Vec3f(1, -2, 0.5f));
    scene.lights.push_back(l);
    test::addPointLight(scene, {0, 5, 0}, Spectrum(1.0f));
    finalizeLights(scene);
    const SceneView view = scene.view();
    LightSample ls;
    ASSERT_TRUE(sampleLight(view, Vec3f(0.5f, 0.2f, 0), 0.25f, Vec2f(0.3f, 0.9f), ls));
    EXPECT_EQ(ls.light, 0u);
    EXPECT_TRUE(ls.delta);
    EXPECT_EQ(ls.pdf, 0.5f);
    EXPECT_EQ(ls.dist, kInfinity);
    EXPECT_NEAR(length(ls.wi + l.direction), 0, 1e-6);
    EXPECT_EQ(ls.Le.r, 3.0f);
    EXPECT_GT(length(ls.p - Vec3f(0.5f, 0.2f, 0)), 2 * 2.0f);  // outside the scene's sphere
    EXPECT_EQ(pdfEnvironmentLight(view, -l.direction), 0.0f);    // not an environment
}

/// Mitsuba 3 allows one environment emitter: constant and envmap together are refused.
TEST(EnvMap, OnlyOneEnvironment) {
    Scene scene;
    test::addConstantLight(scene, Spectrum(1.0f));
    addEnvMap(scene, 4, 3, std::vector<Spectrum>(12, Spectrum(1.0f)));
    EXPECT_THROW(finalizeLights(scene), Error);
}

}  // namespace
}  // namespace caustica
