// principled: eval and pdf against numbers printed by Mitsuba 3.9.1 (scalar_rgb, Python
// bindings: bsdf.eval / bsdf.pdf), χ² goodness-of-fit of its sampling against its pdf with
// per-sample weight == eval/pdf, and its albedo against Mitsuba's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

Bsdf principled(Spectrum base, PrincipledParams p) {
    Bsdf b;
    b.type = BsdfType::Principled;
    b.reflectance = base;
    b.principled = p;
    return b;
}

/// Mitsuba's set A: metallic, spec_tint, sheen(+tint), clearcoat, anisotropic; specular 0.6.
Bsdf setA() {
    PrincipledParams p;
    p.roughness = 0.4f;
    p.metallic = 0.3f, p.hasMetallic = true;
    p.specTint = 0.4f, p.hasSpecTint = true;
    p.sheen = 0.5f, p.hasSheen = true;
    p.sheenTint = 0.3f, p.hasSheenTint = true;
    p.clearcoat = 0.6f, p.hasClearcoat = true;
    p.clearcoatGloss = 0.7f;
    p.anisotropic = 0.5f, p.hasAnisotropic = true;
    p.eta = 2 / (1 - std::sqrt(0.08f * 0.6f)) - 1;
    return principled(Spectrum(0.8f, 0.3f, 0.2f), p);
}

/// Set B: transmission (spec_trans 0.7, eta 1.45).
Bsdf setB() {
    PrincipledParams p;
    p.roughness = 0.3f;
    p.specTrans = 0.7f, p.hasSpecTrans = true;
    p.eta = 1.45f;
    return principled(Spectrum(0.9f, 0.9f, 0.6f), p);
}

/// Set D: flatness 0.5, roughness 0.7.
Bsdf setD() {
    PrincipledParams p;
    p.roughness = 0.7f;
    p.flatness = 0.5f, p.hasFlatness = true;
    return principled(Spectrum(0.2f, 0.6f, 0.3f), p);
}

TEST(Principled, MatchesMitsubaAllReflectionLobes) {
    test::expectMatchesMitsuba(setA(),
                               {{30, 0, 30, 180, {1.428778f, 0.7380742f, 0.5999335f}, 3.170495},
                                {60, 10, 20, 200, {0.3128086f, 0.1258125f, 0.08841332f}, 0.3897664},
                                {5, 0, 70, 90, {0.0630339f, 0.02387845f, 0.01604735f}, 0.0468683},
                                {80, 45, 75, 225, {5.886995f, 4.502602f, 4.225723f}, 8.353796},
                                {40, 20, 150, 190, Spectrum(0.f), 0},
                                {140, 0, 30, 170, Spectrum(0.f), 0},
                                {160, 30, 150, 200, Spectrum(0.f), 2.342063},
                                {20, 0, 25, 160, {0.6464995f, 0.282031f, 0.2091373f}, 1.090711}});
}

TEST(Principled, MatchesMitsubaTransmission) {
    test::expectMatchesMitsuba(
        setB(), {{30, 0, 30, 180, {0.4725645f, 0.4725645f, 0.4477548f}, 2.894272},
                 {60, 10, 20, 200, {0.08346475f, 0.08346475f, 0.05666784f}, 0.08887947},
                 {5, 0, 70, 90, {0.02924467f, 0.02924467f, 0.01956467f}, 0.0265458},
                 {80, 45, 75, 225, {10.32584f, 10.32584f, 10.32042f}, 13.81417},
                 {40, 20, 150, 190, {0.8136519f, 0.8136519f, 0.664344f}, 1.388043},
                 {140, 0, 30, 170, {0.0220626f, 0.0220626f, 0.01801403f}, 0.01581227},
                 {160, 30, 150, 200, Spectrum(0.06124403f), 0.08755048},
                 {20, 0, 25, 160, {0.1815804f, 0.1815804f, 0.1556166f}, 0.8241937}});
}

TEST(Principled, MatchesMitsubaDefaults) {
    PrincipledParams p;  // roughness 0.5, specular 0.5 (eta 1.5), base 0.5
    test::expectMatchesMitsuba(principled(Spectrum(0.5f), p),
                               {{30, 0, 30, 180, Spectrum(0.1982544f), 0.8691483},
                                {60, 10, 20, 200, Spectrum(0.1640797f), 0.3044048},
                                {5, 0, 70, 90, Spectrum(0.05696792f), 0.0722897},
                                {80, 45, 75, 225, Spectrum(1.366188f), 2.57539},
                                {160, 30, 150, 200, Spectrum(0.f), 1.04512},
                                {20, 0, 25, 160, Spectrum(0.1888738f), 0.6983424}});
}

TEST(Principled, MatchesMitsubaFlatness) {
    test::expectMatchesMitsuba(
        setD(), {{30, 0, 30, 180, {0.06274726f, 0.1576713f, 0.08647827f}, 0.3255035},
                 {60, 10, 20, 200, {0.06967191f, 0.1817749f, 0.09769765f}, 0.2999367},
                 {5, 0, 70, 90, {0.023968f, 0.06681705f, 0.03468026f}, 0.09395315},
                 {80, 45, 75, 225, {0.2135182f, 0.2545519f, 0.2237767f}, 0.5182208}});
}

/// Set E: a rough sheen-dominated material (sheen 0.8, sheen_tint 0.6, roughness 0.9), seen at
/// grazing angles where the sheen doubles the value.
Bsdf setE(Float sheen = 0.8f) {
    PrincipledParams p;
    p.roughness = 0.9f;
    p.sheen = sheen, p.hasSheen = true;
    p.sheenTint = 0.6f, p.hasSheenTint = true;
    return principled(Spectrum(0.3f, 0.5f, 0.7f), p);
}

TEST(Principled, MatchesMitsubaSheen) {
    test::expectMatchesMitsuba(
        setE(), {{80, 0, 80, 100, {0.02297925f, 0.03667549f, 0.05037173f}, 0.08300696},
                 {75, 0, 85, 150, {0.01948969f, 0.02637684f, 0.033264f}, 0.07457097},
                 {60, 0, 70, 120, {0.03922601f, 0.06219957f, 0.08517314f}, 0.1087262}});
}

// The comparison has power: sheen 0.8 -> 0.85 moves the value beyond the tolerance (Mitsuba:
// 0.02003166).
TEST(Principled, MitsubaCheckDetectsWrongSheen) {
    const std::vector<Bsdf> bsdfs{setE(0.85f)};
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const Frame frame(si.ns);
    const Spectrum f = evalBsdf(bsdfs, 0, si, test::directionDeg(frame, 75, 0),
                                test::directionDeg(frame, 85, 150));
    EXPECT_FALSE(test::relClose(f.r, 0.01948969, 1e-3)) << f.r;
    EXPECT_TRUE(test::relClose(f.r, 0.02003166, 1e-3)) << f.r;
}

/// χ² of sampleBsdf against pdfBsdf (all lobes are smooth), per-sample weight == eval/pdf.
void runChi2(const std::string& name, const Bsdf& b, double thetaO, double phiO, uint64_t seed) {
    const std::vector<Bsdf> bsdfs{b};
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const Frame frame(si.ns);
    const Vec3f wo = test::directionDeg(frame, thetaO, phiO);
    test::SphereGrid grid;
    grid.frame = frame;
    grid.nTheta = 128;
    grid.nPhi = 256;
    int bad = 0;
    auto sample = [&](int i, Vec3f& w) {
        BsdfSample bs;
        if (!test::sampleBsdfAt(bsdfs, 0, si, wo, i, seed, bs)) return false;
        const Spectrum f = evalBsdf(bsdfs, 0, si, wo, bs.wi);
        const Float pdf = pdfBsdf(bsdfs, 0, si, wo, bs.wi);
        if (bs.delta || !test::relClose(bs.pdf, pdf) ||
            !test::relClose(bs.weight.g, f.g / pdf, 1e-3, 1e-5))
            ++bad;
        w = bs.wi;
        return true;
    };
    auto pdf = [&](Vec3f w) { return double(pdfBsdf(bsdfs, 0, si, wo, w)); };
    const test::Chi2Result r = test::chi2Directions(grid, 1000000, sample, pdf, 4);
    EXPECT_TRUE(r.passed()) << name << ": " << r.describe();
    EXPECT_EQ(bad, 0) << name;
}

TEST(Principled, Chi2ReflectionLobes) {
    runChi2("A_20", setA(), 20, 30, 101);
    runChi2("A_70", setA(), 70, 120, 102);
}

TEST(Principled, Chi2Transmission) {
    runChi2("B_35", setB(), 35, 10, 103);
    runChi2("B_inside", setB(), 140, 60, 104);
}

TEST(Principled, Chi2Flatness) { runChi2("D_50", setD(), 50, 0, 105); }

// White base, dielectric specular: Mitsuba's principled is not energy conserving (Burley's
// diffuse and retro-reflection sit beside the specular lobe): Mitsuba 3.9.1's own albedo
// (40000 samples of bsdf.sample, roughness 0.2) is 1.0295 at normal incidence and 1.0435 at 45°.
// caustica's matches it within the two estimates' errors and gains no more than that.
TEST(Principled, AlbedoMatchesMitsuba) {
    PrincipledParams p;
    p.roughness = 0.2f;
    const std::vector<Bsdf> bsdfs{principled(Spectrum(1.f), p)};
    const SurfaceInteraction si = test::surfaceAt({0, 0, 1});
    const double mitsuba[2] = {1.0295, 1.0435}, mitsubaErr = 0.017;
    int k = 0;
    for (double t : {0.0, 45.0}) {
        const Vec3f wo = test::directionDeg(Frame(si.ns), t, 0);
        double sum = 0, sumSq = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            BsdfSample bs;
            const double w = test::sampleBsdfAt(bsdfs, 0, si, wo, i, 77, bs) ? bs.weight.g : 0;
            sum += w;
            sumSq += w * w;
        }
        const double mean = sum / n, err = std::sqrt((sumSq / n - mean * mean) / n);
        EXPECT_NEAR(mean, mitsuba[k], 4 * std::sqrt(err * err + mitsubaErr * mitsubaErr))
            << "theta " << t;
        EXPECT_LE(mean, 1.06 + 4 * err) << "theta " << t;
        ++k;
    }
}

}  // namespace
}  // namespace caustica
