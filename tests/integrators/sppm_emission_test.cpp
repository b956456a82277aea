// sppm_emission_test.cpp — the photons of sampleEmission (integrators/sppm/sppm_emission.h) for
// every emitter type on small scenes built in code: the mean photon flux (a Monte Carlo estimate
// of the emitted power) against the analytic power within a z-test on its standard error; χ²
// tests of the direction distribution of spot (uniform in the cone), area (cosine about the
// normal) and envmap emission (in the map's uv square, where the density is piecewise constant
// and the expected counts exact); distant lights' rays starting outside the scene's bounds, and
// directional photons parallel to the light with origins uniform on the disk; and
// maxEmissionFlux bounding every photon's largest channel (and tight where it should be).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "caustica/integrators/sppm/sppm_emission.h"
#include "caustica/util/rng.h"
#include "scene/chi2.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

constexpr int kSamples = 400000;

using Mat3 = double[3][3];

/// Rotation about `axis` (normalised here) by `deg` degrees (Rodrigues).
void rotation(Vec3f axis, double deg, Mat3& m) {
    const Vec3f a = normalize(axis);
    const double k[3] = {a.x, a.y, a.z}, th = deg * M_PI / 180, c = std::cos(th), s = std::sin(th);
    const double cross[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = (1 - c) * k[i] * k[j] + (i == j ? c : 0) + s * cross[i][j];
}

double det3(const Mat3& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/// Rows of the inverse of `m` (cofactors over the determinant).
void inverseRows(const Mat3& m, Vec3f (&rows)[3]) {
    const double det = det3(m);
    for (int i = 0; i < 3; ++i) {
        double r[3];
        for (int j = 0; j < 3; ++j) {  // inv[i][j] = cofactor(j, i) / det
            const int a0 = (i + 1) % 3, a1 = (i + 2) % 3, b0 = (j + 1) % 3, b1 = (j + 2) % 3;
            r[j] = (m[b0][a0] * m[b1][a1] - m[b0][a1] * m[b1][a0]) / det;
        }
        rows[i] = Vec3f(Float(r[0]), Float(r[1]), Float(r[2]));
    }
}

/// A spot light (Mitsuba 3's spot) at `pos` whose to_world linear part is `toWorld`.
Light makeSpot(Spectrum intensity, Vec3f pos, double cutoffDeg, double beamDeg,
               const Mat3& toWorld) {
    Light l;
    l.type = LightType::Spot;
    l.radiance = intensity;
    l.position = pos;
    const double cutoff = cutoffDeg * M_PI / 180, beam = beamDeg * M_PI / 180;
    l.cutoff = Float(cutoff);
    l.cosCutoff = Float(std::cos(cutoff));
    l.cosBeam = Float(std::cos(beam));
    l.invTransition = beam < cutoff ? Float(1 / (cutoff - beam)) : Float(0);
    l.uvFactor = Float(std::tan(cutoff));
    inverseRows(toWorld, l.localFromWorld);
    return l;
}

/// An envmap light over `w` x `h` texels (row-major, top row first) rotated by `rot`.
uint32_t addEnvMap(Scene& scene, int w, int h, const std::vector<Spectrum>& texels,
                   const Mat3& rot) {
    Matrix4 m, mInv;  // a rotation: the inverse is the transpose
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            m.m[r][c] = Float(rot[r][c]);
            mInv.m[c][r] = Float(rot[r][c]);
        }
    return test::addEnvMap(scene, w, h, texels, Transform(m, mInv));
}

/// A 12x7 map: a gradient, a black band (zero probability), a bright texel and one on the seam.
std::vector<Spectrum> envTexels() {
    std::vector<Spectrum> t;
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 12; ++x) {
            Spectrum v(0.2f + 0.1f * x, 0.5f, 0.3f + 0.2f * y);
            if (x >= 3 && x <= 5) v = Spectrum(0.0f);
            if (x == 8 && y == 2) v = Spectrum(30, 20, 10);
            if (x == 11 && y == 4) v = Spectrum(8.0f);
            t.push_back(v);
        }
    return t;
}

/// Geometry for the distant lights to enclose: a sphere and a rectangle (no emitters).
void addGeometry(Scene& scene) {
    test::addSphere(scene, {0.3f, -0.2f, 0.5f}, 1.0f);
    const test::RectMesh rect({-2, -1, -1}, {3, 0, 0}, {0, 0, 2.5f});
    test::addMesh(scene, rect.positions, rect.triangles);
}

/// Photon i of a run with `seed`, its numbers drawn in the photon pass's order.
bool emit(const SceneView& view, int i, uint64_t seed, EmissionSample& e) {
    IndependentSampler rng(uint64_t(i), 0, seed);
    const Float uSelect = rng.get1D();
    const Vec2f uPos = rng.get2D();
    const Vec2f uDir = rng.get2D();
    return sampleEmission(view, uSelect, uPos, uDir, e);
}

/// Chi-square test of the directions of kSamples photons (stream `seed`) against `pdf`.
template <class Pdf>
test::Chi2Result chi2EmittedDirections(const Scene& scene, const test::SphereGrid& grid, uint64_t seed, Pdf pdf) {
    const SceneView view = scene.view();
    return test::chi2Directions(
        grid, kSamples,
        [&](int i, Vec3f& w) {
            EmissionSample e;
            if (!emit(view, i, seed, e)) return false;
            w = normalize(e.ray.d);
            return true;
        },
        pdf);
}

/// Mean photon flux per channel over kSamples photons (failed samples count as zero), its
/// standard error, and the checks every photon must pass: finite non-negative flux, a unit
/// direction, a max channel within maxEmissionFlux.
struct PowerEstimate {
    double mean[3] = {0, 0, 0}, se[3] = {0, 0, 0};
    double bound = 0, maxFlux = 0;
    int invalid = 0, overBound = 0;
};

PowerEstimate estimatePower(const Scene& scene, uint64_t seed,
                            const std::function<void(const EmissionSample&)>& check = {}) {
    const SceneView view = scene.view();
    PowerEstimate p;
    p.bound = maxEmissionFlux(view);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < kSamples; ++i) {
        EmissionSample e;
        if (!emit(view, i, seed, e)) continue;
        const double f[3] = {e.flux.r, e.flux.g, e.flux.b};
        for (int c = 0; c < 3; ++c) {
            if (!(f[c] >= 0) || !std::isfinite(f[c])) ++p.invalid;
            sum[c] += f[c];
            sum2[c] += f[c] * f[c];
        }
        if (std::fabs(length(e.ray.d) - 1) > 1e-5f) ++p.invalid;
        p.maxFlux = std::max(p.maxFlux, double(e.flux.maxValue()));
        if (e.flux.maxValue() > p.bound * (1 + 1e-5)) ++p.overBound;
        if (check) check(e);
    }
    for (int c = 0; c < 3; ++c) {
        p.mean[c] = sum[c] / kSamples;
        p.se[c] = std::sqrt(std::max(0.0, sum2[c] / kSamples - p.mean[c] * p.mean[c]) / kSamples);
    }
    return p;
}

/// The estimate agrees with `power` per channel (z-test at the suite's per-check significance,
/// plus float rounding for the zero-variance estimators), no photon is invalid or above the
/// bound, and (when `tight`) the bound is no more than `tight` times the largest photon.
void expectPower(const PowerEstimate& p, const double (&power)[3], const std::string& what,
                 double tight = 0) {
    const double z = test::normalUpperQuantile(test::kChi2Significance / 2);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(p.mean[c], power[c], z * p.se[c] + 1e-5 * std::fabs(power[c]))
            << what << ", channel " << c << " (standard error " << p.se[c] << ")";
    EXPECT_EQ(p.invalid, 0) << what;
    EXPECT_EQ(p.overBound, 0) << what << ": bound " << p.bound << ", largest photon " << p.maxFlux;
    if (std::getenv("CAUSTICA_CHI2_VERBOSE"))
        std::printf("%s: bound / largest photon = %.4f\n", what.c_str(), p.bound / p.maxFlux);
    if (tight > 0) {
        EXPECT_LE(p.bound, tight * p.maxFlux) << what << ": the bound is loose";
    }
}

/// Channel c (0, 1, 2) of s.
double channel(Spectrum s, int c) {
    return c == 0 ? s.r : c == 1 ? s.g : s.b;
}

/// power = Le (or I, E) times `factor`, per channel.
void scaled(Spectrum s, double factor, double (&out)[3]) {
    for (int c = 0; c < 3; ++c) out[c] = channel(s, c) * factor;
}

/// Whether `o` lies outside the scene's bounding box and on or outside its bounding sphere.
bool startsOutside(const Scene& scene, const Light& l, Vec3f o) {
    const Bounds3f b = scene.bounds();
    const bool outBox = o.x < b.lo.x || o.y < b.lo.y || o.z < b.lo.z || o.x > b.hi.x ||
                        o.y > b.hi.y || o.z > b.hi.z;
    return outBox && length(o - l.sceneCenter) >= l.sceneRadius * (1 - 1e-6f);
}

/// ∫ I(ω) dω of a spot over world directions, by Simpson quadrature over its local cone: a
/// world direction is to_world's A l / |A l|, dω_world = |det A| / |A l|³ dω_local.
double spotPowerQuadrature(const Scene& scene, const Light& l, const Mat3& a, int c) {
    const TextureView tex = scene.view().textureView();
    const double det = det3(a);
    const double beam = std::acos(double(l.cosBeam));
    auto integrate = [&](double t0, double t1) {  // θ in [t0, t1]: falloff smooth inside
        const int nt = 400, np = 512;
        double sum = 0;
        for (int i = 0; i <= nt; ++i) {
            // Nodes on the ends moved 1e-5 rad inside: the falloff's limit from inside the cone.
            const double th = t0 + (t1 - t0) * i / nt + (i == 0 ? 1e-5 : i == nt ? -1e-5 : 0);
            double ring = 0;
            for (int j = 0; j < np; ++j) {  // periodic in φ: the trapezoid rule
                const double ph = 2 * M_PI * j / np;
                const double lc[3] = {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                      std::cos(th)};
                double w[3];
                for (int r = 0; r < 3; ++r)
                    w[r] = a[r][0] * lc[0] + a[r][1] * lc[1] + a[r][2] * lc[2];
                const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
                const Vec3f wf(Float(w[0] / len), Float(w[1] / len), Float(w[2] / len));
                ring += channel(spotIntensity(l, tex, wf), c) * std::fabs(det) / (len * len * len);
            }
            sum += test::simpsonWeight(i, nt) * ring * std::sin(th) * (2 * M_PI / np);
        }
        return sum * (t1 - t0) / nt / 3;
    };
    return integrate(0, beam) + integrate(beam, double(l.cutoff));
}

/// ∫ Le(ω) dω of an envmap per channel, by the midpoint rule in its uv square
/// (dω = 2π² sinθ du dv).
void envMapIntegral(const Scene& scene, const Light& l, double (&out)[3]) {
    const SceneView view = scene.view();
    const int nu = 2400, nv = 1200;
    double sum[3] = {0, 0, 0};
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            Float sinTheta;
            const Vec3f local = envmap_detail::uvToDirection(
                Vec2f(Float((i + 0.5) / nu), Float((j + 0.5) / nv)), sinTheta);
            const Spectrum le = envMapRadiance(view, l, applyRows(l.worldFromLocal, local));
            sum[0] += le.r * sinTheta;
            sum[1] += le.g * sinTheta;
            sum[2] += le.b * sinTheta;
        }
    for (int c = 0; c < 3; ++c) out[c] = sum[c] * 2 * M_PI * M_PI / (double(nu) * nv);
}

TEST(SppmEmission, AreaLightsEmitLeTimesPiTimesArea) {
    const Spectrum le(2, 1, 0.5f);
    for (int kind = 0; kind < 4; ++kind) {
        Scene scene;
        double area = 0;
        if (kind < 2) {  // a mesh of four unequal triangles, either side
            const test::RectMesh rect({0, 1, 0}, {2, 0, 0}, {0, 0.5f, 1.5f});
            test::addAreaLight(scene,
                               test::addMesh(scene, rect.positions, rect.triangles, kind == 1), le);
            area = length(cross(rect.u, rect.v));
        } else if (kind == 2) {
            test::addAreaLight(scene, test::addSphere(scene, {1, 2, 3}, 0.7f, true), le);
            area = 4 * M_PI * 0.49;
        } else {
            test::addAreaLight(scene, test::addCylinder(scene, {0, 0, 0}, {1, 1, 0}, 0.3f, 2), le);
            area = 2 * M_PI * 0.3 * 2;
        }
        finalizeLights(scene);
        double power[3];
        scaled(le, M_PI * area, power);
        expectPower(estimatePower(scene, 31 + kind), power, "area kind " + std::to_string(kind),
                    1.0001);
    }
}

TEST(SppmEmission, PointLightEmits4PiI) {
    Scene scene;
    test::addPointLight(scene, {1, -2, 0.5f}, Spectrum(3, 2, 1));
    finalizeLights(scene);
    double power[3];
    scaled(Spectrum(3, 2, 1), 4 * M_PI, power);
    expectPower(estimatePower(scene, 41), power, "point", 1.0001);
}

TEST(SppmEmission, SpotEmitsTheIntegralOfItsFalloff) {
    Mat3 rot;
    rotation({1, 2, 3}, 50, rot);
    const Spectrum intensity(4, 2, 1);
    const std::pair<double, double> cases[] = {{30, 20}, {30, 30}, {120, 5}};  // cutoff, beam
    for (const auto& [cutoff, beam] : cases) {
        Scene scene;
        const Light l = makeSpot(intensity, {0.5f, 1, -1}, cutoff, beam, rot);
        scene.lights.push_back(l);
        finalizeLights(scene);
        // Mitsuba's falloff integrated: 2π [1 - (sin c - sin β) / (c - β)];
        // a hard edge (c = β): 2π (1 - cos c).
        const double c = cutoff * M_PI / 180, b = beam * M_PI / 180;
        const double omega = c > b ? 2 * M_PI * (1 - (std::sin(c) - std::sin(b)) / (c - b))
                                   : 2 * M_PI * (1 - std::cos(c));
        double power[3];
        scaled(intensity, omega, power);
        const std::string what = "spot " + std::to_string(cutoff) + "/" + std::to_string(beam);
        EXPECT_NEAR(spotPowerQuadrature(scene, scene.lights[0], rot, 0), power[0], 1e-4 * power[0]);
        expectPower(estimatePower(scene, 51 + uint64_t(cutoff + beam)), power, what, 1.0001);
    }
}

/// A spot whose to_world scales unevenly (the world cone is no longer round: the photon's
/// direction density carries the Jacobian) and one with a bitmap texture over the cone.
TEST(SppmEmission, SpotWithScaledTransformOrTextureEmitsItsPower) {
    Mat3 rot, a;
    rotation({-1, 0.5f, 2}, 35, rot);
    const double scale[3] = {1.0, 2.5, 0.6};
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) a[r][k] = rot[r][k] * scale[k];  // to_world = R · S
    for (bool textured : {false, true}) {
        Scene scene;
        Light l = makeSpot(Spectrum(1, 2, 3), {0, 0, 0}, 40, 25, textured ? rot : a);
        if (textured) {
            Texture t;
            t.type = TextureType::Bitmap;
            t.width = 4;
            t.height = 3;
            for (int i = 0; i < 12; ++i)
                scene.texels.push_back(Spectrum(0.1f * Float(i), 1.0f, i == 6 ? 5.0f : 0.5f));
            scene.textures.push_back(t);
            l.texture = 0;
        }
        scene.lights.push_back(l);
        finalizeLights(scene);
        double power[3];
        for (int c = 0; c < 3; ++c) power[c] = spotPowerQuadrature(scene, l, textured ? rot : a, c);
        // The bound over-estimates a non-rigid transform's Jacobian by up to 3^(3/4).
        expectPower(estimatePower(scene, 61 + textured), power,
                    textured ? "textured spot" : "scaled spot", textured ? 1.05 : 2.3);
    }
}

TEST(SppmEmission, DirectionalEmitsIrradianceTimesTheDiskAndStartsOutside) {
    Scene scene;
    addGeometry(scene);
    Light l;
    l.type = LightType::Directional;
    l.radiance = Spectrum(3, 2, 1);
    l.direction = normalize(Vec3f(1, -2, 0.5f));
    scene.lights.push_back(l);
    finalizeLights(scene);
    const Light& fl = scene.lights[0];
    int outside = 0, parallel = 0;
    std::vector<double> rho2;  // squared distance to the disk's centre over R²: uniform on [0, 1)
    const PowerEstimate p = estimatePower(scene, 71, [&](const EmissionSample& e) {
        outside += startsOutside(scene, fl, e.ray.o);
        parallel += length(e.ray.d - fl.direction) < 1e-6f;
        const Vec3f q = e.ray.o - fl.sceneCenter;
        const Vec3f perp = q - fl.direction * dot(q, fl.direction);
        rho2.push_back(double(lengthSquared(perp)) / (double(fl.sceneRadius) * fl.sceneRadius));
    });
    double power[3];
    scaled(fl.radiance, M_PI * fl.sceneRadius * fl.sceneRadius, power);
    expectPower(p, power, "directional", 1.0001);
    EXPECT_EQ(outside, kSamples);
    EXPECT_EQ(parallel, kSamples);
    const test::Chi2Result r = test::chi2UniformOnUnitInterval(
        64, int(rho2.size()), [&](int i) { return std::min(rho2[size_t(i)], 1 - 1e-12); });
    EXPECT_TRUE(r.passed()) << "disk radius: " << r.describe();
}

TEST(SppmEmission, ConstantEmits4PiLeTimesTheDiskAndStartsOutside) {
    Scene scene;
    addGeometry(scene);
    test::addConstantLight(scene, Spectrum(0.5f, 1, 2));
    finalizeLights(scene);
    const Light& l = scene.lights[0];
    int outside = 0;
    const PowerEstimate p = estimatePower(
        scene, 81, [&](const EmissionSample& e) { outside += startsOutside(scene, l, e.ray.o); });
    double power[3];
    scaled(l.radiance, 4 * M_PI * M_PI * l.sceneRadius * l.sceneRadius, power);
    expectPower(p, power, "constant", 1.0001);
    EXPECT_EQ(outside, kSamples);
    // The photons travel along -wi, wi uniform on the sphere: uniform as well.
    test::SphereGrid grid;
    grid.frame = Frame(Vec3f(0, 0, 1));
    grid.nTheta = 16;
    grid.nPhi = 32;
    const test::Chi2Result r = chi2EmittedDirections(scene, grid, 82, [](Vec3f) { return 1 / (4 * M_PI); });
    EXPECT_TRUE(r.passed()) << r.describe();
}

Scene envMapScene() {
    Scene scene;
    addGeometry(scene);
    Mat3 rot;
    rotation({1, 2, 3}, 50, rot);
    addEnvMap(scene, 12, 7, envTexels(), rot);
    finalizeLights(scene);
    return scene;
}

TEST(SppmEmission, EnvMapEmitsTheDiskTimesTheIntegralOfLeAndStartsOutside) {
    const Scene scene = envMapScene();
    const Light& l = scene.lights[0];
    int outside = 0;
    const PowerEstimate p = estimatePower(
        scene, 91, [&](const EmissionSample& e) { outside += startsOutside(scene, l, e.ray.o); });
    double power[3];
    envMapIntegral(scene, l, power);
    for (double& v : power) v *= M_PI * l.sceneRadius * l.sceneRadius;
    expectPower(p, power, "envmap", 1.5);  // 1.22: the bound sits on patch corners
    EXPECT_EQ(outside, kSamples);
}

/// Every type at once: each light is chosen with probability 1/5, so the mean is the sum.
TEST(SppmEmission, MixedScenePowerIsTheSumOfTheLights) {
    Scene scene = envMapScene();
    const test::RectMesh rect({0, 1, 0}, {2, 0, 0}, {0, 0.5f, 1.5f});
    test::addAreaLight(scene, test::addMesh(scene, rect.positions, rect.triangles),
                       Spectrum(2, 1, 0.5f));
    test::addPointLight(scene, {1, -2, 0.5f}, Spectrum(3, 2, 1));
    Mat3 rot;
    rotation({0, 1, 0}, 20, rot);
    scene.lights.push_back(makeSpot(Spectrum(4, 2, 1), {0, 2, 0}, 30, 30, rot));
    Light d;
    d.type = LightType::Directional;
    d.radiance = Spectrum(0.3f, 0.2f, 0.1f);
    d.direction = normalize(Vec3f(0, -1, 0.2f));
    scene.lights.push_back(d);
    finalizeLights(scene);
    const double r2 = double(scene.lights[0].sceneRadius) * scene.lights[0].sceneRadius;
    const double omegaSpot = 2 * M_PI * (1 - std::cos(30 * M_PI / 180));
    double power[3];
    envMapIntegral(scene, scene.lights[0], power);
    for (int c = 0; c < 3; ++c) {
        power[c] = M_PI * r2 * power[c] +
                   channel(scene.lights[1].radiance, c) * M_PI * length(cross(rect.u, rect.v)) +
                   channel(scene.lights[2].radiance, c) * 4 * M_PI +
                   channel(scene.lights[3].radiance, c) * omegaSpot +
                   channel(scene.lights[4].radiance, c) * M_PI *
                       double(scene.lights[4].sceneRadius) * scene.lights[4].sceneRadius;
    }
    expectPower(estimatePower(scene, 101), power, "mixed", 2);  // 1.44: the envmap sets it
}

TEST(SppmEmissionChi2, SpotDirectionsAreUniformInTheCone) {
    Mat3 rot;
    rotation({1, 2, 3}, 50, rot);
    Scene scene;
    scene.lights.push_back(makeSpot(Spectrum(1.0f), {0, 0, 0}, 30, 20, rot));
    finalizeLights(scene);
    const Vec3f axis = normalize(Vec3f(Float(rot[0][2]), Float(rot[1][2]), Float(rot[2][2])));
    const double cutoff = 30 * M_PI / 180, cosCutoff = std::cos(cutoff);
    const double pdf = 1 / (2 * M_PI * (1 - cosCutoff));
    test::SphereGrid grid;
    grid.frame = Frame(axis);
    grid.thetaMax = cutoff;
    grid.nTheta = 16;
    grid.nPhi = 32;
    const test::Chi2Result r =
        chi2EmittedDirections(scene, grid, 111, [&](Vec3f w) { return dot(w, axis) > cosCutoff ? pdf : 0.0; });
    EXPECT_TRUE(r.passed()) << r.describe();
}

TEST(SppmEmissionChi2, AreaDirectionsAreCosineDistributed) {
    Scene scene;
    const test::RectMesh rect({0, 1, 0}, {2, 0, 0}, {0, 0.5f, 1.5f});
    test::addAreaLight(scene, test::addMesh(scene, rect.positions, rect.triangles), Spectrum(1.0f));
    finalizeLights(scene);
    const Vec3f n = normalize(cross(rect.u, rect.v));
    test::SphereGrid grid;
    grid.frame = Frame(n);
    grid.thetaMax = M_PI / 2;
    grid.nTheta = 16;
    grid.nPhi = 32;
    const test::Chi2Result r =
        chi2EmittedDirections(scene, grid, 121, [&](Vec3f w) { return std::max(0.0, double(dot(w, n))) / M_PI; });
    EXPECT_TRUE(r.passed()) << r.describe();
}

/// χ² in the map's uv square: the photon travels along -wi; cells are quarters of the bilinear
/// patches, where envMapSample's density is constant, so a quarter expects pRow · pCol / 4.
TEST(SppmEmissionChi2, EnvMapDirectionsFollowTheMap) {
    const Scene scene = envMapScene();
    const SceneView view = scene.view();
    const Light& l = scene.lights[0];
    const int W = int(l.texWidth), H = int(l.texHeight), nu = 2 * W, nv = 2 * (H - 1);
    std::vector<double> obs(size_t(nu) * nv + 1, 0.0), expected(obs.size(), 0.0);
    for (int i = 0; i < kSamples; ++i) {
        EmissionSample e;
        if (!emit(view, i, 131, e)) {
            obs.back() += 1;
            continue;
        }
        const Vec3f local = normalize(applyRows(l.localFromWorld, -e.ray.d));
        const Vec2f g = envmap_detail::uvToGrid(l, envmap_detail::directionToUv(local));
        const int cu = std::min(int(g.x * 2), nu - 1), cv = std::min(int(g.y * 2), nv - 1);
        obs[size_t(cv) * nu + cu] += 1;
    }
    for (int j = 0; j + 1 < H; ++j) {
        const double pRow = discreteCdfPmf(envmap_detail::marginalCdf(view, l), uint32_t(j));
        for (int i = 0; i < W; ++i) {
            const double p =
                pRow * discreteCdfPmf(envmap_detail::rowCdf(view, l, uint32_t(j)), uint32_t(i));
            for (int q = 0; q < 4; ++q)
                expected[size_t(2 * j + q / 2) * nu + size_t(2 * i + q % 2)] = p / 4 * kSamples;
        }
    }
    expected.back() = kSamples * 0x1p-20;  // as SphereGrid: a sample refused on a pole
    const test::Chi2Result r = test::chi2Test(obs, expected);
    EXPECT_TRUE(r.passed()) << r.describe();
}

}  // namespace
}  // namespace caustica
