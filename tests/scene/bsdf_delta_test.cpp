// Fresnel terms and the delta BSDFs (smooth dielectric and conductor): lobe probabilities,
// weights, Snell's law, total internal reflection, and Mitsuba's "none" conductor.
#include <gtest/gtest.h>

#include <complex>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

/// Reference unpolarised Fresnel reflectance for complex relative IOR n (double precision,
/// the textbook amplitude coefficients: Born and Wolf, Principles of Optics, 1.5.2 and 14.2).
double fresnelReference(double cosI, std::complex<double> n) {
    const double sin2 = 1 - cosI * cosI;
    const std::complex<double> cosT = std::sqrt(n * n - sin2);  // times n: n cosθt
    const std::complex<double> rs = (cosI - cosT) / (cosI + cosT);
    const std::complex<double> rp = (n * n * cosI - cosT) / (n * n * cosI + cosT);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}

TEST(Fresnel, DielectricMatchesReference) {
    for (double eta : {1.33, 1.5046, 2.4, 1 / 1.5})
        for (int i = 0; i <= 100; ++i) {
            const double cosI = double(Float(i / 100.0));  // the float the code sees
            const FresnelDielectric f = fresnelDielectric(Float(cosI), Float(eta));
            const double sin2T = (1 - cosI * cosI) / (eta * eta);
            const double ref = sin2T >= 1 ? 1.0 : fresnelReference(cosI, eta);
            EXPECT_NEAR(f.r, ref, 2e-6) << "eta " << eta << " cos " << cosI;
            EXPECT_NEAR(f.cosThetaT, sin2T >= 1 ? 0.0 : -std::sqrt(1 - sin2T), 2e-6);
            EXPECT_FLOAT_EQ(f.etaIT, Float(eta));
            EXPECT_FLOAT_EQ(f.etaTI, Float(1 / eta));
        }
}

TEST(Fresnel, DielectricSpecialCases) {
    const Float eta = 1.5f;
    EXPECT_NEAR(fresnelDielectric(1, eta).r, sqr((eta - 1) / (eta + 1)), 1e-7f);
    EXPECT_EQ(fresnelDielectric(0, eta).r, 1.0f);  // grazing
    EXPECT_EQ(fresnelDielectric(0.3f, 1.0f).r, 0.0f);  // index matched
    // From inside the roles swap: the same interface seen from the dense side.
    const FresnelDielectric in = fresnelDielectric(-0.9f, eta);
    EXPECT_FLOAT_EQ(in.etaIT, 1 / eta);
    EXPECT_GT(in.cosThetaT, 0.0f);
    // Reciprocity: the refracted direction sees the same reflectance from the other side.
    const FresnelDielectric out = fresnelDielectric(0.6f, eta);
    EXPECT_NEAR(fresnelDielectric(out.cosThetaT, eta).r, out.r, 1e-6f);
    // Total internal reflection beyond the critical angle sinθc = 1/η.
    const Float cosCrit = std::sqrt(1 - 1 / (eta * eta));
    const FresnelDielectric tir = fresnelDielectric(-(cosCrit - 0.01f), eta);
    EXPECT_EQ(tir.r, 1.0f);
    EXPECT_EQ(tir.cosThetaT, 0.0f);
    EXPECT_LT(fresnelDielectric(-(cosCrit + 0.01f), eta).r, 1.0f);
}

TEST(Fresnel, ConductorMatchesReference) {
    const double etas[][2] = {{0.143, 3.983}, {0.2, 3.0}, {1.5, 0.0}, {2.5, 1.0}, {0.05, 0.3}};
    for (const auto& e : etas)
        for (int i = 0; i <= 100; ++i) {
            const double cosI = double(Float(i / 100.0));
            const double ref = fresnelReference(cosI, std::complex<double>(e[0], e[1]));
            EXPECT_NEAR(fresnelConductor(Float(cosI), Float(e[0]), Float(e[1])), ref, 1e-5)
                << e[0] << "+" << e[1] << "i, cos " << cosI;
        }
    // k = 0 is a dielectric.
    EXPECT_NEAR(fresnelConductor(0.7f, 1.5f, 0.0f), fresnelDielectric(0.7f, 1.5f).r, 1e-6f);
}

TEST(Fresnel, NoneConductorReflectsEverything) {
    for (int i = 0; i <= 20; ++i)
        EXPECT_EQ(fresnelConductor(i / 20.0f, 0.0f, 1.0f), 1.0f) << i;
}

TEST(Conductor, WeightIsFresnelAndDirectionIsMirror) {
    const Spectrum eta(0.2f, 0.9f, 1.1f), k(3.9f, 2.4f, 1.6f), r(0.9f, 0.8f, 0.7f);
    std::vector<Bsdf> bsdfs{test::conductor(eta, k, r),
                            test::conductor(Spectrum(0.f), Spectrum(1.f))};
    const Bsdf none = bsdfs[1], colored = bsdfs[0];  // copies: addTwoSided grows the vector
    const uint32_t twoSided = test::addTwoSided(bsdfs, none, colored);
    const SurfaceInteraction si = test::surfaceAt(Vec3f(-0.3f, 0.4f, 0.8f));
    const Frame frame(si.ns);
    for (double theta : {0.0, 30.0, 60.0, 89.0}) {
        const Vec3f wo = test::directionDeg(frame, theta, 70);
        const Vec3f mirror = si.ns * (2 * dot(wo, si.ns)) - wo;
        BsdfSample bs;
        ASSERT_TRUE(sampleBsdf(bsdfs, 0, si, wo, 0.5f, Vec2f(0.1f, 0.2f), bs));
        EXPECT_TRUE(bs.delta);
        EXPECT_EQ(bs.pdf, 1.0f);
        EXPECT_EQ(bs.eta, 1.0f);
        EXPECT_NEAR(length(bs.wi - mirror), 0.0f, 1e-5f);
        const Spectrum f = fresnelConductor(dot(wo, si.ns), eta, k) * r;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(bs.weight[c], f[c], 1e-6f);
        EXPECT_TRUE(evalBsdf(bsdfs, 0, si, wo, bs.wi).isBlack());
        EXPECT_EQ(pdfBsdf(bsdfs, 0, si, wo, bs.wi), 0.0f);
        // Mitsuba's default "none" material (η = 0, κ = 1) reflects 100%.
        ASSERT_TRUE(sampleBsdf(bsdfs, 1, si, wo, 0.5f, Vec2f(0.1f, 0.2f), bs));
        EXPECT_EQ(bs.weight.r, 1.0f);
        EXPECT_EQ(bs.weight.g, 1.0f);
        EXPECT_EQ(bs.weight.b, 1.0f);
        // Twosided: from the back, the back child reflects about -n.
        ASSERT_TRUE(sampleBsdf(bsdfs, twoSided, si, -mirror, 0.5f, Vec2f(0.1f, 0.2f), bs));
        EXPECT_NEAR(length(bs.wi + wo), 0.0f, 1e-5f);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(bs.weight[c], f[c], 1e-6f);
    }
    BsdfSample bs;
    EXPECT_FALSE(sampleBsdf(bsdfs, 0, si, -si.ns, 0.5f, Vec2f(0.1f, 0.2f), bs));
}

/// Smooth dielectric at one incident direction: lobe frequencies (binomial test against F),
/// weights, pdfs, relative IOR and the geometry of both lobes.
void checkDielectric(Float etaRatio, Vec3f n, double thetaO, uint64_t seed) {
    const Spectrum r(0.9f, 0.8f, 0.7f), t(0.6f, 0.5f, 0.4f);
    const std::vector<Bsdf> bsdfs{test::dielectric(etaRatio, r, t)};
    const SurfaceInteraction si = test::surfaceAt(n);
    const Frame frame(si.ns);
    const Vec3f wo = test::directionDeg(frame, thetaO, 40);
    const Float cosO = dot(wo, si.ns);
    const FresnelDielectric f = fresnelDielectric(cosO, etaRatio);
    const Float etaIT = cosO >= 0 ? etaRatio : 1 / etaRatio;  // η_t / η_i for the crossing

    constexpr int kTrials = 200000;
    int reflections = 0;
    for (int i = 0; i < kTrials; ++i) {
        BsdfSample bs;
        ASSERT_TRUE(test::sampleBsdfAt(bsdfs, 0, si, wo, i, seed, bs));
        ASSERT_TRUE(bs.delta);
        const Float cosI = dot(bs.wi, si.ns);
        ASSERT_NEAR(length(bs.wi), 1.0f, 1e-5f);
        if (cosI * cosO > 0) {  // reflection: the mirror direction
            ++reflections;
            ASSERT_NEAR(length(bs.wi - (si.ns * (2 * cosO) - wo)), 0.0f, 1e-5f);
            ASSERT_FLOAT_EQ(bs.pdf, f.r);
            ASSERT_EQ(bs.eta, 1.0f);
            for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(bs.weight[c], r[c]);
        } else {  // refraction: Snell's law in the plane of incidence, radiance scaled by 1/η²
            const Float sinO = std::sqrt(max(0.0f, 1 - cosO * cosO));
            const Float sinI = std::sqrt(max(0.0f, 1 - cosI * cosI));
            ASSERT_NEAR(sinO, etaIT * sinI, 2e-5f);
            ASSERT_NEAR(cosI, f.cosThetaT, 1e-5f);
            // In the plane of incidence, on the other side of the normal.
            const Vec3f tO = wo - si.ns * cosO, tI = bs.wi - si.ns * cosI;
            ASSERT_NEAR(dot(cross(tO, tI), si.ns), 0.0f, 1e-5f);
            ASSERT_LE(dot(tO, tI), 1e-6f);
            ASSERT_FLOAT_EQ(bs.pdf, 1 - f.r);
            ASSERT_FLOAT_EQ(bs.eta, etaIT);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(bs.weight[c], t[c] / (etaIT * etaIT), 1e-6f);
        }
        ASSERT_TRUE(evalBsdf(bsdfs, 0, si, wo, bs.wi).isBlack());
        ASSERT_EQ(pdfBsdf(bsdfs, 0, si, wo, bs.wi), 0.0f);
    }
    const double p = test::binomialPValue(reflections, kTrials, f.r);
    EXPECT_GE(p, test::kChi2Significance)
        << reflections << " reflections of " << kTrials << ", F = " << f.r;
}

TEST(Dielectric, LobesFollowFresnelFromOutside) {
    uint64_t seed = 100;
    for (double theta : {0.0, 30.0, 60.0, 85.0})
        checkDielectric(1.5046f, normalize(Vec3f(0.2f, -0.1f, 1)), theta, seed++);
}

TEST(Dielectric, LobesFollowFresnelFromInside) {
    // Below the critical angle (41.6° for η = 1.5046): both lobes.
    checkDielectric(1.5046f, Vec3f(0, 0, 1), 180 - 20, 200);
    checkDielectric(1.33f, Vec3f(0, 1, 0), 180 - 40, 201);
}

TEST(Dielectric, TotalInternalReflection) {
    const std::vector<Bsdf> bsdfs{test::dielectric(1.5046f)};
    const SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    const Vec3f wo = test::directionDeg(Frame(si.ns), 180 - 50, 0);  // beyond 41.6°
    for (Float u : {0.0f, 0.5f, 0.999999f}) {
        BsdfSample bs;
        ASSERT_TRUE(sampleBsdf(bsdfs, 0, si, wo, u, Vec2f(0.5f, 0.5f), bs));
        EXPECT_EQ(bs.pdf, 1.0f);
        EXPECT_EQ(bs.eta, 1.0f);
        EXPECT_LT(bs.wi.z, 0.0f);  // stays inside
        EXPECT_NEAR(bs.wi.z, wo.z, 1e-6f);
        EXPECT_EQ(bs.weight.r, 1.0f);
    }
}

TEST(Dielectric, IndexMatchedOnlyRefracts) {
    const std::vector<Bsdf> bsdfs{test::dielectric(1.0f)};
    const SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    const Vec3f wo = test::directionDeg(Frame(si.ns), 35, 20);
    BsdfSample bs;
    ASSERT_TRUE(sampleBsdf(bsdfs, 0, si, wo, 0.0f, Vec2f(0.5f, 0.5f), bs));
    EXPECT_EQ(bs.pdf, 1.0f);
    EXPECT_NEAR(length(bs.wi + wo), 0.0f, 1e-6f);  // straight through
}

/// Mitsuba's thindielectric from either side: reflection with probability R = 2F / (1 + F)
/// (binomial test), weight specular_reflectance; otherwise straight through (wi = -wo, η = 1),
/// weight specular_transmittance; no smooth part.
TEST(ThinDielectric, LobesAndWeights) {
    const Spectrum r(0.9f, 0.8f, 0.7f), t(0.6f, 0.5f, 0.4f);
    const std::vector<Bsdf> bsdfs{test::thinDielectric(1.5046f, r, t)};
    EXPECT_TRUE(isDeltaBsdf(bsdfs, 0));
    const SurfaceInteraction si = test::surfaceAt(Vec3f(0.1f, 0.2f, 1));
    uint64_t seed = 400;
    for (double theta : {0.0, 40.0, 80.0, 120.0, 175.0}) {
        const Vec3f wo = test::directionDeg(Frame(si.ns), theta, 15);
        const Float cosO = dot(wo, si.ns);
        const Float f = fresnelDielectric(std::fabs(cosO), 1.5046f).r;
        const Float reflect = 2 * f / (1 + f);
        constexpr int kTrials = 100000;
        int reflections = 0;
        for (int i = 0; i < kTrials; ++i) {
            BsdfSample bs;
            ASSERT_TRUE(test::sampleBsdfAt(bsdfs, 0, si, wo, i, seed, bs));
            ASSERT_TRUE(bs.delta);
            ASSERT_EQ(bs.eta, 1.0f);
            if (dot(bs.wi, si.ns) * cosO > 0) {
                ++reflections;
                ASSERT_NEAR(length(bs.wi - (si.ns * (2 * cosO) - wo)), 0.0f, 1e-5f);
                ASSERT_FLOAT_EQ(bs.pdf, reflect);
                for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(bs.weight[c], r[c]);
            } else {
                ASSERT_NEAR(length(bs.wi + wo), 0.0f, 1e-6f);
                ASSERT_FLOAT_EQ(bs.pdf, 1 - reflect);
                for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(bs.weight[c], t[c]);
            }
            ASSERT_TRUE(evalBsdf(bsdfs, 0, si, wo, bs.wi).isBlack());
            ASSERT_EQ(pdfBsdf(bsdfs, 0, si, wo, bs.wi), 0.0f);
        }
        ++seed;
        const double p = test::binomialPValue(reflections, kTrials, reflect);
        EXPECT_GE(p, test::kChi2Significance) << theta << ": " << reflections << " vs R = " << reflect;
    }
}

}  // namespace
}  // namespace caustica
