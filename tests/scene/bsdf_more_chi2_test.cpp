// roughplastic, blendbsdf, mask, null and twosided around them: χ² goodness-of-fit of sampleBsdf
// against pdfBsdf (smooth samples), per-sample consistency of the sampled weight and pdf with
// evalBsdf / pdfBsdf, delta samples (mirror or straight through), and values against numbers
// printed by Mitsuba 3.9.1 (scalar_rgb, through its Python bindings).
#include <gtest/gtest.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "scene/bsdf_more_util.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

using Chi2Case = test::BsdfChi2Case;

uint64_t seedOf(const std::string& name) {
    uint64_t h = 0x84222325cbf29ce4ull;
    for (char ch : name) h = (h ^ uint8_t(ch)) * 0x100000001b3ull;
    return h;
}

void runChi2(const Chi2Case& c) {
    const Span<const Bsdf> bsdfs(c.bsdfs);
    const test::BsdfChi2View v(c);
    const SurfaceInteraction& si = v.si;
    const Vec3f wo = v.wo;
    test::BsdfSampleCheck check;
    int badDelta = 0;
    auto keep = [&](const BsdfSample& bs) {
        if (bs.delta) {  // a mirror or a straight pass-through, outside the histogram
            const bool ok =
                length(bs.wi - test::mirrorOf(si, wo)) < 1e-4f || length(bs.wi + wo) < 1e-4f;
            if (!ok || !(bs.pdf > 0) || !bs.weight.isValid()) ++badDelta;
            return false;
        }
        check.check(bsdfs, c.id, si, wo, bs);
        return true;
    };
    const test::Chi2Result r =
        test::bsdfChi2(bsdfs, bsdfs, c.id, si, wo, v.grid, seedOf(c.name), c.k, keep);
    EXPECT_TRUE(r.passed()) << c.name << ": " << r.describe();
    test::printChi2IfVerbose(c.name, r);
    EXPECT_EQ(check.badWeight, 0) << c.name << ": " << check.firstBad;
    EXPECT_EQ(check.badPdf, 0) << c.name;
    EXPECT_EQ(badDelta, 0) << c.name;
}

/// A case by name, built when its test runs: building a roughplastic tabulates its albedo (seconds),
/// which every process of this test executable would otherwise pay at start-up.
struct LazyCase {
    std::string name;
    std::function<Chi2Case()> make;
};

std::vector<LazyCase> makeCases() {
    using test::blend;
    std::vector<LazyCase> cases;
    const Spectrum base(0.2f, 0.5f, 0.8f);
    for (MicrofacetType type : {MicrofacetType::Beckmann, MicrofacetType::GGX})
        for (Float a : {0.1f, 0.4f})
            for (double t : {0.0, 40.0, 75.0}) {
                const std::string name = std::string("roughplastic_") +
                                         (type == MicrofacetType::GGX ? "ggx" : "beckmann") + "_a" +
                                         std::to_string(int(a * 100)) + "_" + std::to_string(int(t));
                cases.push_back({name, [=] {
                                     Chi2Case c{name,
                                                {makeRoughPlastic(type, a, 1.49f, base, Spectrum(1.f), false)},
                                                0, {0, 0, 1}, t, 20};
                                     if (a < 0.2f) c.nTheta = 128, c.nPhi = 256;
                                     return c;
                                 }});
            }
    cases.push_back({"roughplastic_nonlinear_tilted", [] {
                         return Chi2Case{"roughplastic_nonlinear_tilted",
                                         {makeRoughPlastic(MicrofacetType::GGX, 0.3f, 1.7f,
                                                           Spectrum(0.9f, 0.1f, 0.4f), Spectrum(0.6f), true)},
                                         0, {0.2f, 0.4f, 1}, 55, 100};
                     }});
    cases.push_back({"blend_diffuse_roughconductor", [] {
                         Chi2Case c{"blend_diffuse_roughconductor", {}, 0, {0, 0, 1}, 35, 10};
                         c.id = blend(c.bsdfs, 0.3f, test::diffuse(Spectrum(0.7f)), test::roughConductor(0.2f, 0.2f));
                         return c;
                     }});
    // the smooth part of a blend with a delta child (its samples' pdf is the mixture's)
    cases.push_back({"blend_diffuse_conductor", [] {
                         Chi2Case c{"blend_diffuse_conductor", {}, 0, {0, 0, 1}, 50, 0};
                         c.id = blend(c.bsdfs, 0.6f, test::diffuse(Spectrum(0.7f)),
                                      test::conductor(Spectrum(0.2f), Spectrum(3.f)));
                         return c;
                     }});
    cases.push_back({"mask_roughplastic", [=] {
                         Chi2Case c{"mask_roughplastic", {}, 0, {0, 0, 1}, 60, 30, 128, 256};
                         c.id = test::mask(c.bsdfs, 0.65f,
                                           makeRoughPlastic(MicrofacetType::Beckmann, 0.1f, 1.49f, base,
                                                            Spectrum(1.f), false));
                         return c;
                     }});
    // twosided(blend(diffuse, roughconductor)) seen from the back, and a nested tree
    cases.push_back({"twosided_blend_back", [] {
                         Chi2Case c{"twosided_blend_back", {}, 0, {0, 0, 1}, 130, 40};
                         const uint32_t b =
                             blend(c.bsdfs, 0.5f, test::diffuse(Spectrum(0.6f)), test::roughConductor(0.1f, 0.4f));
                         c.id = test::twoSidedOf(c.bsdfs, b, b);
                         return c;
                     }});
    cases.push_back({"nested_blend_mask", [=] {
                         Chi2Case n{"nested_blend_mask", {}, 0, {0.3f, 0, 1}, 45, 200};
                         const uint32_t inner = blend(n.bsdfs, 0.25f, test::diffuse(Spectrum(0.9f)),
                                                      makeRoughPlastic(MicrofacetType::GGX, 0.5f, 1.5f, base,
                                                                       Spectrum(1.f), true));
                         n.bsdfs.push_back(test::roughConductor(0.3f, 0.3f));
                         const uint32_t masked = test::maskOf(n.bsdfs, 0.5f, uint32_t(n.bsdfs.size() - 1));
                         n.id = test::blendOf(n.bsdfs, 0.7f, inner, masked);
                         return n;
                     }});
    return cases;
}

/// gtest prints a case by its name (not as the bytes of its std::function).
void PrintTo(const LazyCase& c, std::ostream* os) { *os << c.name; }

class BsdfMoreChi2 : public ::testing::TestWithParam<LazyCase> {};

TEST_P(BsdfMoreChi2, SamplingMatchesPdf) { runChi2(GetParam().make()); }

INSTANTIATE_TEST_SUITE_P(LayeredAndComposite, BsdfMoreChi2, ::testing::ValuesIn(makeCases()),
                         [](const ::testing::TestParamInfo<LazyCase>& info) { return info.param.name; });

// eval and pdf of Mitsuba 3.9.1's roughplastic (python: bsdf.eval / bsdf.pdf).
TEST(RoughPlastic, MatchesMitsubaBeckmannDefault) {
    test::expectMatchesMitsuba(makeRoughPlastic(MicrofacetType::Beckmann, 0.1f, 1.49f / 1.000277f,
                                                Spectrum(0.2f, 0.5f, 0.8f), Spectrum(1.f), false),
                               {{30, 0, 30, 180, {0.4229319f, 0.5036167f, 0.5843015f}, 0.9683276},
                                {60, 10, 20, 200, {0.05547844f, 0.1386946f, 0.2219107f}, 0.250109},
                                {5, 0, 70, 90, {0.01841912f, 0.04604779f, 0.07367647f}, 0.1007591},
                                {80, 45, 80, 225, {17.69018f, 17.69744f, 17.70471f}, 24.12914}},
                               2e-3);
}

TEST(RoughPlastic, MatchesMitsubaGgxNonlinear) {
    test::expectMatchesMitsuba(makeRoughPlastic(MicrofacetType::GGX, 0.3f, 1.6f / 1.000277f,
                                                Spectrum(0.9f, 0.4f, 0.1f), Spectrum(0.7f), true),
                               {{30, 0, 30, 180, {0.1840891f, 0.08467992f, 0.04846443f}, 0.3487576},
                                {60, 10, 20, 200, {0.1626999f, 0.06107961f, 0.02405856f}, 0.306142},
                                {5, 0, 70, 90, {0.05272972f, 0.01778988f, 0.005061043f}, 0.1033871},
                                {80, 45, 80, 225, {0.6666434f, 0.6537853f, 0.649101f}, 1.185215}},
                               2e-3);
}

TEST(RoughPlastic, MatchesMitsubaRoughWater) {
    test::expectMatchesMitsuba(makeRoughPlastic(MicrofacetType::Beckmann, 0.6f, 1.49f / 1.333f,
                                                Spectrum(0.5f), Spectrum(1.f), false),
                               {{30, 0, 30, 180, Spectrum(0.1183215f), 0.275382},
                                {60, 10, 20, 200, Spectrum(0.1255265f), 0.3047934},
                                {5, 0, 70, 90, Spectrum(0.04336639f), 0.1089861},
                                {80, 45, 80, 225, Spectrum(0.1310844f), 0.2989857}},
                               2e-3);
}

// The check has power: a slightly different IOR moves the values beyond the tolerance.
TEST(RoughPlastic, MitsubaCheckDetectsWrongIor) {
    const std::vector<Bsdf> bsdfs{makeRoughPlastic(MicrofacetType::Beckmann, 0.6f, 1.55f / 1.333f,
                                                   Spectrum(0.5f), Spectrum(1.f), false)};
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const Frame frame(si.ns);
    const Spectrum f = evalBsdf(bsdfs, 0, si, test::directionDeg(frame, 5, 0),
                                test::directionDeg(frame, 70, 90));
    EXPECT_FALSE(test::relClose(f.r, 0.04336639, 2e-3)) << f.r;
}

/// Mitsuba 3.9.1's blendbsdf (weight 0.3) of diffuse 0.5 and a perfect mirror, wi = normalize(0.3,
/// 0.1, 0.9): choosing the mirror (sample1 0.1) returns pdf 0.5102180 (0.3 + 0.7 · cosθ/π) and
/// weight 0.793992 ((0.3 · 1 + 0.7 · f_d) / pdf); the diffuse choice is the mixture's eval/pdf.
TEST(BlendBsdf, DeltaChildMatchesMitsuba) {
    std::vector<Bsdf> bsdfs;
    const uint32_t id = test::blend(bsdfs, 0.3f, test::diffuse(Spectrum(0.5f)),
                                    test::conductor(Spectrum(0.f), Spectrum(1.f)));
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const Vec3f wo = normalize(Vec3f(0.3f, 0.1f, 0.9f));
    BsdfSample bs;
    ASSERT_TRUE(sampleBsdf(bsdfs, id, si, wo, 0.1f, Vec2f(0.3f, 0.6f), bs));
    EXPECT_TRUE(bs.delta);
    EXPECT_NEAR(bs.pdf, 0.5102180, 1e-5);
    EXPECT_NEAR(bs.weight.r, 0.793992, 1e-5);
    ASSERT_TRUE(sampleBsdf(bsdfs, id, si, wo, 0.5f, Vec2f(0.3f, 0.6f), bs));
    EXPECT_FALSE(bs.delta);
    EXPECT_NEAR(bs.weight.r, 0.5, 1e-5);
}

/// Mitsuba's mask: the nested BSDF with probability opacity (pdf scaled, weight unchanged), else
/// straight through with pdf 1 - opacity and weight 1; null always passes.
TEST(Mask, ChoosesLikeMitsuba) {
    std::vector<Bsdf> bsdfs;
    const uint32_t id = test::mask(bsdfs, 0.3f, test::diffuse(Spectrum(0.5f)));
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const Vec3f wo = normalize(Vec3f(0.3f, 0.1f, 0.9f));
    BsdfSample bs;
    ASSERT_TRUE(sampleBsdf(bsdfs, id, si, wo, 0.29f, Vec2f(0.3f, 0.6f), bs));
    EXPECT_FALSE(bs.delta);
    EXPECT_NEAR(bs.weight.r, 0.5, 1e-6);
    EXPECT_NEAR(bs.pdf, 0.3 * bs.wi.z / M_PI, 1e-6);
    ASSERT_TRUE(sampleBsdf(bsdfs, id, si, wo, 0.3f, Vec2f(0.3f, 0.6f), bs));
    EXPECT_TRUE(bs.delta);
    EXPECT_NEAR(length(bs.wi + wo), 0, 1e-6);
    EXPECT_NEAR(bs.pdf, 0.7, 1e-6);
    EXPECT_EQ(bs.weight.r, 1.0f);
    EXPECT_FALSE(isDeltaBsdf(bsdfs, id));
    std::vector<Bsdf> nulls{test::nullBsdf()};
    ASSERT_TRUE(sampleBsdf(nulls, 0, si, wo, 0.99f, Vec2f(0.3f, 0.6f), bs));
    EXPECT_TRUE(bs.delta && bs.pdf == 1 && bs.weight.r == 1 && bs.eta == 1);
    EXPECT_NEAR(length(bs.wi + wo), 0, 1e-6);
    EXPECT_TRUE(isDeltaBsdf(nulls, 0));
    EXPECT_EQ(evalBsdf(nulls, 0, si, wo, -wo).r, 0.0f);
}

/// NEE is skipped only when every leaf is delta.
TEST(BsdfComposite, IsDelta) {
    std::vector<Bsdf> b;
    const uint32_t smooth = test::blend(b, 0.5f, test::diffuse(Spectrum(0.5f)),
                                        test::conductor(Spectrum(0.f), Spectrum(1.f)));
    EXPECT_FALSE(isDeltaBsdf(b, smooth));
    const uint32_t delta =
        test::blend(b, 0.5f, test::dielectric(1.5f), test::conductor(Spectrum(0.f), Spectrum(1.f)));
    EXPECT_TRUE(isDeltaBsdf(b, delta));
    EXPECT_TRUE(isDeltaBsdf(b, test::mask(b, 0.5f, test::conductor(Spectrum(0.f), Spectrum(1.f)))));
    b.push_back(test::diffuse(Spectrum(0.5f)));
    const uint32_t d = uint32_t(b.size() - 1);
    b.push_back(test::conductor(Spectrum(0.f), Spectrum(1.f)));
    const uint32_t m = uint32_t(b.size() - 1);
    EXPECT_FALSE(isDeltaBsdf(b, test::twoSidedOf(b, m, d)));  // the back side is smooth
    EXPECT_TRUE(isDeltaBsdf(b, test::twoSidedOf(b, m, m)));
}

}  // namespace
}  // namespace caustica
