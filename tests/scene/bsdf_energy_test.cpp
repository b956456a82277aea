// Energy tests: the Monte Carlo albedo ∫ f |cosθi| dω of every BSDF with white parameters is at
// most 1 (exactly 1 for the white diffuse), estimated both by the BSDF's own sampling and by
// uniform sampling of evalBsdf; the smooth dielectric conserves flux exactly.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

constexpr int kSamples = 200000;

/// Mean and standard error of a sample.
struct Estimate {
    double sum = 0, sumSq = 0;
    int n = 0;
    void add(double v) { sum += v, sumSq += v * v, ++n; }
    double mean() const { return sum / n; }
    double stdErr() const { return std::sqrt(std::max(0.0, sumSq / n - sqr(mean())) / n); }
};

struct EnergyCase {
    std::string name;
    std::vector<Bsdf> bsdfs;
    uint32_t id = 0;
    bool uniformCheck = true;  // compare with uniform sampling (off for very peaked lobes)
};

std::vector<EnergyCase> energyCases() {
    std::vector<EnergyCase> c;
    c.push_back({"diffuse", {test::diffuse(Spectrum(1.f))}});
    c.push_back({"rough_a5", {test::roughConductor(0.05f, 0.05f)}, 0, false});
    c.push_back({"rough_a30", {test::roughConductor(0.3f, 0.3f)}});
    c.push_back({"rough_a80", {test::roughConductor(0.8f, 0.8f)}});
    c.push_back({"rough_aniso", {test::roughConductor(0.1f, 0.5f)}, 0, false});
    EnergyCase two{"twosided", {}};
    two.id = test::addTwoSided(two.bsdfs, test::diffuse(Spectrum(1.f)),
                               test::roughConductor(0.3f, 0.3f));
    c.push_back(two);
    return c;
}

TEST(BsdfEnergy, AlbedoAtMostOne) {
    const double z = test::normalUpperQuantile(test::kChi2Significance);
    const SurfaceInteraction si = test::surfaceAt(Vec3f(0.1f, 0.3f, 1));
    const Frame frame(si.ns);
    uint64_t seed = 1000;
    for (const EnergyCase& c : energyCases())
        for (double theta : {0.0, 30.0, 60.0, 85.0, 150.0}) {
            const bool front = theta < 90;
            if (!front && c.bsdfs[c.id].type != BsdfType::TwoSided) continue;
            const Vec3f wo = test::directionDeg(frame, theta, 25);
            const std::string at = c.name + " at " + std::to_string(int(theta));
            Estimate sampled, uniform;
            double maxWeight = 0;
            for (int i = 0; i < kSamples; ++i) {
                IndependentSampler rng(uint64_t(i), 0, seed);
                const Float uLobe = rng.get1D();
                const Vec2f u = rng.get2D();
                BsdfSample bs;
                const double w =
                    sampleBsdf(c.bsdfs, c.id, si, wo, uLobe, u, bs) ? bs.weight.g : 0.0;
                sampled.add(w);
                maxWeight = std::max(maxWeight, w);
                // Independent estimator: uniform directions on the sphere, f cos / (1/4π).
                const Vec3f wi = sampleUniformSphere(rng.get2D());
                uniform.add(evalBsdf(c.bsdfs, c.id, si, wo, wi).g / uniformSpherePdf());
            }
            ++seed;
            // White parameters: no single sample may carry more than the incident energy.
            EXPECT_LE(maxWeight, 1 + 1e-5) << at;
            EXPECT_LE(sampled.mean(), 1 + z * sampled.stdErr() + 1e-6) << at;
            if (c.uniformCheck) {
                const double se = std::sqrt(sqr(sampled.stdErr()) + sqr(uniform.stdErr()));
                EXPECT_LE(std::fabs(sampled.mean() - uniform.mean()), z * se + 1e-6)
                    << at << ": sampled " << sampled.mean() << " uniform " << uniform.mean();
            }
            if (c.name == "diffuse" || (c.name == "twosided" && front)) {
                EXPECT_NEAR(sampled.mean(), 1.0, 1e-6) << at;  // every weight is exactly 1
                EXPECT_LE(std::fabs(uniform.mean() - 1), z * uniform.stdErr()) << at;
            }
        }
}

// A smooth rough conductor loses little energy at normal incidence (single scattering): the
// albedo of GGX α = 0.05 is within 1% of 1, and roughness only loses energy.
TEST(BsdfEnergy, RoughConductorLosesEnergyWithRoughness) {
    const SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    const Vec3f wo = test::directionDeg(Frame(si.ns), 10, 0);
    double prev = 2;
    for (Float a : {0.05f, 0.3f, 0.8f}) {
        const std::vector<Bsdf> b{test::roughConductor(a, a)};
        Estimate e;
        for (int i = 0; i < kSamples; ++i) {
            IndependentSampler rng(uint64_t(i), 0, 2000);
            const Float uLobe = rng.get1D();
            BsdfSample bs;
            e.add(sampleBsdf(b, 0, si, wo, uLobe, rng.get2D(), bs) ? bs.weight.r : 0.0);
        }
        if (a == 0.05f) {
            EXPECT_GT(e.mean(), 0.99);
        }
        EXPECT_LT(e.mean(), prev);
        prev = e.mean();
    }
}

// Smooth dielectric, white: every sample's flux weight (the radiance weight times η'² for a
// refraction) is exactly 1, and the radiance weight averages to F + (1 - F) / η'².
TEST(BsdfEnergy, DielectricConservesFlux) {
    const double z = test::normalUpperQuantile(test::kChi2Significance);
    const std::vector<Bsdf> b{test::dielectric(1.5046f)};
    const SurfaceInteraction si = test::surfaceAt(Vec3f(0.3f, 0, 1));
    uint64_t seed = 3000;
    for (double theta : {0.0, 45.0, 80.0, 160.0, 130.0}) {
        const Vec3f wo = test::directionDeg(Frame(si.ns), theta, 60);
        const FresnelDielectric f = fresnelDielectric(dot(wo, si.ns), 1.5046f);
        const double expected = f.r + (1 - f.r) * sqr(double(f.etaTI));
        Estimate radiance;
        int badFlux = 0;
        for (int i = 0; i < kSamples; ++i) {
            IndependentSampler rng(uint64_t(i), 0, seed);
            const Float uLobe = rng.get1D();
            BsdfSample bs;
            ASSERT_TRUE(sampleBsdf(b, 0, si, wo, uLobe, rng.get2D(), bs));
            radiance.add(bs.weight.r);
            if (std::fabs(bs.weight.r * sqr(bs.eta) - 1) > 1e-5f) ++badFlux;
        }
        ++seed;
        EXPECT_EQ(badFlux, 0) << theta;
        EXPECT_LE(std::fabs(radiance.mean() - expected), z * radiance.stdErr() + 1e-6)
            << theta << ": " << radiance.mean() << " vs " << expected;
    }
}

}  // namespace
}  // namespace caustica
