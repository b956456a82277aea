// The photon paths' roulette (sppmPhotonSurvival, integrators/sppm/sppm_photon.h) in a closed box
// of grey diffuse walls (albedo a) around a point light, where every quantity has a closed form:
// the k-th hit (k >= 2 segments from the light, where photons are stored) receives an expected
// flux of Φ a^(k-1) under either rule. With "albedo" every stored photon carries exactly the
// emitted Φ (a bounce's survival is its albedo and the survivor is divided by it), with
// "throughput" photons dim as a^(k-1) until rr_depth; the expected flux a path stores and the
// expected rays it traces are checked against their sums within a z-test, which a rule that
// forgot to divide by the survival probability (or rouletted twice) fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/sppm/sppm_passes.h"
#include "integrators/lane_test_scene.h"
#include "scene/scene_builder.h"

namespace caustica::test {
namespace {

constexpr Float kAlbedo = 0.5f;
constexpr uint32_t kMaxDepth = 12;
constexpr uint64_t kIteration = 2, kSeed = 5;

/// The lane tests' box x, y in [-1, 1], z in [0, 2] with its walls facing in, every wall diffuse
/// with albedo kAlbedo, a point light of intensity 1 at its centre: Φ = 4π per photon.
Scene makeGreyBox() {
    Scene scene;
    Bsdf grey;
    grey.reflectance = Spectrum(kAlbedo);
    scene.bsdfs = {grey};
    const Vec3f centre(0, 0, 1);
    auto rect = [&](Vec3f o, Vec3f u, Vec3f v) {  // its normal cross(u, v) turned to the centre
        if (dot(cross(u, v), centre - o) < 0) std::swap(u, v);
        RectMesh r(o, u, v);
        return addMesh(scene, r.positions, r.triangles);
    };
    addBoxWalls(rect);
    addPointLight(scene, centre, Spectrum(1));
    finalizeLights(scene);
    return scene;
}

/// Over `paths` photon paths: mean and standard error of the red flux a path stores (over Φ) and
/// of the rays it traces, photons stored per path, and the largest |flux / Φ - 1| of one photon.
struct Moments {
    double fluxMean = 0, fluxError = 0, raysMean = 0, raysError = 0, photonsPerPath = 0, worstPowerError = 0;
};

Moments tracePaths(const Scene& scene, PhotonRoulette roulette, uint64_t paths) {
    const Accel accel(scene, AccelKind::Bvh);
    const SceneView& view = accel.sceneView();
    const double phi = 4 * M_PI;
    const SppmPhotonRules rules{PathSettings{}, kMaxDepth, Float(0), roulette};
    double sf = 0, sf2 = 0, sr = 0, sr2 = 0;
    uint64_t photons = 0;
    double worst = 0;
    accel.visit([&](const auto& it) {
        std::vector<uint64_t> rayBlocks(size_t(paths / 1024 + 1), 0);
        for (uint64_t i = 0; i < paths; ++i) {
            const uint64_t raysBefore = rayBlocks[i / 1024];
            double flux = 0;
            sppm_detail::photonPath(view, it, size_t(i), kIteration, kSeed, rules, rayBlocks.data(),
                                    [&](const SurfaceInteraction&, Vec3f, const Spectrum& f, uint32_t) {
                                        flux += double(f.r) / phi;
                                        worst = std::max(worst, std::fabs(double(f.r) / phi - 1));
                                        ++photons;
                                    });
            const double rays = double(rayBlocks[i / 1024] - raysBefore);
            sf += flux, sf2 += flux * flux, sr += rays, sr2 += rays * rays;
        }
    });
    const double n = double(paths);
    Moments m;
    m.fluxMean = sf / n;
    m.fluxError = std::sqrt(std::max(0.0, sf2 / n - m.fluxMean * m.fluxMean) / n);
    m.raysMean = sr / n;
    m.raysError = std::sqrt(std::max(0.0, sr2 / n - m.raysMean * m.raysMean) / n);
    m.photonsPerPath = double(photons) / n;
    m.worstPowerError = worst;
    return m;
}

/// Σ_{k=2}^{kMaxDepth-1} a^(k-1): the expected stored flux of a path over Φ (hits k = 2 ..
/// kMaxDepth - 1 store; the hit at kMaxDepth - 1 traces nothing further).
double expectedFlux() {
    double sum = 0;
    for (uint32_t k = 2; k + 1 <= kMaxDepth; ++k) sum += std::pow(double(kAlbedo), double(k - 1));
    return sum;
}

TEST(SppmPhotonRoulette, AlbedoRuleKeepsEveryPhotonsPowerAndTheExpectedFlux) {
    const Moments m = tracePaths(makeGreyBox(), PhotonRoulette::Albedo, 200000);
    std::printf("albedo: flux %.5f +- %.5f (expected %.5f), rays %.4f, photons %.4f per path\n", m.fluxMean,
                m.fluxError, expectedFlux(), m.raysMean, m.photonsPerPath);
    EXPECT_LT(m.worstPowerError, 1e-4);  // every photon carries Φ
    EXPECT_NEAR(m.fluxMean, expectedFlux(), 5 * m.fluxError);
    // A path survives each bounce with probability a: rays 1 + a + ... + a^(kMaxDepth-2).
    double rays = 0;
    for (uint32_t j = 0; j + 2 <= kMaxDepth; ++j) rays += std::pow(double(kAlbedo), double(j));
    EXPECT_NEAR(m.raysMean, rays, 5 * m.raysError);
}

TEST(SppmPhotonRoulette, ThroughputRuleStoresTheSameExpectedFluxWithDimmerPhotonsAndMoreRays) {
    const Scene scene = makeGreyBox();
    const Moments t = tracePaths(scene, PhotonRoulette::Throughput, 200000);
    const Moments a = tracePaths(scene, PhotonRoulette::Albedo, 20000);
    std::printf("throughput: flux %.5f +- %.5f (expected %.5f), rays %.4f, photons %.4f per path\n", t.fluxMean,
                t.fluxError, expectedFlux(), t.raysMean, t.photonsPerPath);
    EXPECT_NEAR(t.fluxMean, expectedFlux(), 5 * t.fluxError);
    // Until rr_depth (5) nothing ends a path in the closed box: at least 4 rays, photons at
    // a, a^2, a^3 of Φ.
    EXPECT_GE(t.raysMean, 4.0);
    EXPECT_GT(t.worstPowerError, 0.8);
    EXPECT_GT(t.raysMean, a.raysMean + 2.0);
}

}  // namespace
}  // namespace caustica::test
