// Energy of roughplastic, blendbsdf, mask and null: the albedo (mean sample weight, delta lobes
// included) of white materials is at most 1 within its Monte Carlo error, and the composites of
// white lossless BSDFs pass a white furnace (every sample's weight exactly 1 where Mitsuba's
// estimator allows it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "scene/bsdf_more_util.h"
#include "scene/bsdf_test_util.h"

namespace caustica {
namespace {

constexpr int kSamples = 200000;

struct Albedo {
    double mean = 0, stdErr = 0, maxWeight = 0;
};

/// Mean of the sampled weights (green channel) from `wo` at θ degrees, absorbed samples as 0.
Albedo albedo(const std::vector<Bsdf>& bsdfs, uint32_t id, double theta, uint64_t seed) {
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const Vec3f wo = test::directionDeg(Frame(si.ns), theta, 30);
    double sum = 0, sumSq = 0, maxW = 0;
    for (int i = 0; i < kSamples; ++i) {
        BsdfSample bs;
        double w = 0;
        if (test::sampleBsdfAt(bsdfs, id, si, wo, i, seed, bs)) w = bs.weight.g;
        sum += w;
        sumSq += w * w;
        maxW = std::max(maxW, w);
    }
    Albedo a;
    a.mean = sum / kSamples;
    a.stdErr = std::sqrt(std::max(0.0, sumSq / kSamples - a.mean * a.mean) / kSamples);
    a.maxWeight = maxW;
    return a;
}

// Mitsuba's roughplastic with a white base: its diffuse term divides by 1 - R_int (internal
// reflections summed) with R_int and the transmittance table from the same quadrature, so the
// albedo stays below 1 (no gain); checked at several roughnesses, IORs and angles.
TEST(RoughPlasticEnergy, WhiteBaseDoesNotGain) {
    for (MicrofacetType type : {MicrofacetType::Beckmann, MicrofacetType::GGX})
        for (Float a : {0.05f, 0.5f})
            for (Float eta : {1.2f, 2.0f}) {
                const std::vector<Bsdf> b{
                    makeRoughPlastic(type, a, eta, Spectrum(1.f), Spectrum(1.f), false)};
                for (double t : {0.0, 45.0, 80.0}) {
                    const Albedo r = albedo(b, 0, t, 17);
                    EXPECT_LE(r.mean, 1 + 4 * r.stdErr + 1e-3)
                        << "alpha " << a << " eta " << eta << " theta " << t;
                    EXPECT_GT(r.mean, 0.3) << "alpha " << a << " eta " << eta << " theta " << t;
                }
            }
}

// A black base keeps only the coating's rough reflection, at most 1 and below 1 at normal
// incidence (F0 = 4% for η 1.5 plus multiple-scattering loss).
TEST(RoughPlasticEnergy, CoatingAloneIsFresnel) {
    const std::vector<Bsdf> b{
        makeRoughPlastic(MicrofacetType::GGX, 0.2f, 1.5f, Spectrum(0.f), Spectrum(1.f), false)};
    const Albedo r = albedo(b, 0, 0, 3);
    EXPECT_NEAR(r.mean, 0.04, 0.01);
}

// White furnace: mask over a white diffuse, null, and a blend of two white diffuse BSDFs send
// every sample on with weight 1 (the pass-through carries the rest).
TEST(CompositeEnergy, WhiteFurnace) {
    std::vector<Bsdf> b;
    const uint32_t m = test::mask(b, 0.4f, test::diffuse(Spectrum(1.f)));
    const uint32_t n = test::append(b, test::nullBsdf());
    const uint32_t bl =
        test::blend(b, 0.35f, test::diffuse(Spectrum(1.f)), test::diffuse(Spectrum(1.f)));
    const uint32_t nested = test::blendOf(b, 0.5f, m, bl);
    for (uint32_t id : {m, n, bl, nested})
        for (double t : {10.0, 60.0}) {
            const Albedo r = albedo(b, id, t, 5 + id);
            EXPECT_NEAR(r.mean, 1.0, 1e-5) << "bsdf " << id << " theta " << t;
            EXPECT_LE(r.maxWeight, 1 + 1e-5) << "bsdf " << id;
        }
}

// Blends and masks of lossy or rough BSDFs keep the energy of their children (no gain).
TEST(CompositeEnergy, NoGain) {
    std::vector<Bsdf> b;
    const uint32_t bl = test::blend(b, 0.5f, test::roughConductor(0.3f, 0.3f),
                                    makeRoughPlastic(MicrofacetType::Beckmann, 0.2f, 1.5f,
                                                     Spectrum(0.9f), Spectrum(1.f), false));
    const uint32_t m = test::mask(b, 0.7f, test::roughDielectric(1.5f, 0.3f, 0.3f));
    for (uint32_t id : {bl, m})
        for (double t : {0.0, 50.0, 85.0}) {
            const Albedo r = albedo(b, id, t, 11 + id);
            EXPECT_LE(r.mean, 1 + 4 * r.stdErr + 1e-3) << "bsdf " << id << " theta " << t;
        }
}

}  // namespace
}  // namespace caustica
