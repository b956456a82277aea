// SPPM's pieces (integrators/sppm/): the per-pixel radius and flux update against values computed
// by hand, the image formula, the fixed point of the deposits, the photons' emitted flux, and
// the settings refused with file:line (or option) and reason.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "caustica/integrators/integrator_params.h"
#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/scene/bsdf.h"
#include "caustica/util/error.h"

namespace caustica::test {
namespace {

TEST(SppmUpdate, RadiusAndFluxAsComputedByHand) {
    // N = 0, R = 1, τ = 0; M = 3 photons with Phi = (6, 3, 0), α = 2/3:
    // N' = 0 + 2/3 · 3 = 2, R' = 1 · sqrt(2 / 3), τ' = (0 + Phi) · (R'/R)² = Phi · 2/3.
    SppmPixel p;
    p.radius = 1;
    const double phi[3] = {6, 3, 0};
    sppmUpdatePixel(p, phi, 3, 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(p.n, 2.0);
    EXPECT_DOUBLE_EQ(p.radius, std::sqrt(2.0 / 3.0));
    EXPECT_DOUBLE_EQ(p.tau[0], 4.0);
    EXPECT_DOUBLE_EQ(p.tau[1], 2.0);
    EXPECT_DOUBLE_EQ(p.tau[2], 0.0);
    // Second iteration: M = 1, Phi = (1, 1, 1): N' = 2 + 2/3 = 8/3, R'² = R² · (8/3) / 3 = 2/3 · 8/9
    // = 16/27, τ' = (τ + 1) · (8/9): (40/9, 3 · 8/9, 8/9).
    const double phi2[3] = {1, 1, 1};
    sppmUpdatePixel(p, phi2, 1, 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(p.n, 8.0 / 3.0);
    EXPECT_NEAR(p.radius * p.radius, 16.0 / 27.0, 1e-15);
    EXPECT_NEAR(p.tau[0], 40.0 / 9.0, 1e-14);
    EXPECT_NEAR(p.tau[1], 24.0 / 9.0, 1e-14);
    EXPECT_NEAR(p.tau[2], 8.0 / 9.0, 1e-14);
}

TEST(SppmUpdate, NoPhotonsChangeNothingAndAlphaOneKeepsTheRadius) {
    SppmPixel p;
    p.radius = 0.5;
    p.n = 7;
    p.tau[0] = 3;
    const double zero[3] = {0, 0, 0};
    sppmUpdatePixel(p, zero, 0, 0.5);
    EXPECT_EQ(p.radius, 0.5);
    EXPECT_EQ(p.n, 7);
    EXPECT_EQ(p.tau[0], 3);
    const double phi[3] = {2, 0, 0};
    sppmUpdatePixel(p, phi, 4, 1.0);  // α = 1: every photon kept, plain PPM density estimate
    EXPECT_DOUBLE_EQ(p.radius, 0.5);
    EXPECT_DOUBLE_EQ(p.n, 11);
    EXPECT_DOUBLE_EQ(p.tau[0], 5);
}

TEST(SppmUpdate, ImageIsDirectMeanPlusFluxOverPhotonsTimesDiscArea) {
    SppmPixel p;
    p.ld[0] = 8;  // over 4 iterations: 2
    p.tau[0] = 3.0 * 3.14159265358979323846;
    p.radius = 0.5;  // π R² = π / 4
    double L[3];
    sppmPixelRadiance(p, 4, 3, 4, L);  // τ / (4 · 3 · π/4) = 3π / (3π) = 1
    EXPECT_DOUBLE_EQ(L[0], 3.0);
    EXPECT_DOUBLE_EQ(L[1], 0.0);
}

TEST(SppmFixedPointTest, RoundsNonNegativeValuesAndDropsInvalidOnes) {
    SppmFixedPoint f;
    f.scale = 4294967296.0;  // Φmax = 1
    EXPECT_EQ(f.toUnits(1.0f), 4294967296ull);
    EXPECT_EQ(f.toUnits(0.5f), 2147483648ull);
    EXPECT_EQ(f.toUnits(-1.0f), 0u);
    EXPECT_EQ(f.toUnits(std::nanf("")), 0u);
    EXPECT_EQ(f.toUnits(1e30f), 4503599627370496ull);  // clamped to 2^52 units
    EXPECT_DOUBLE_EQ(f.toValue(f.toUnits(0.25f)), 0.25);
}

IntegratorSpec sppmSpec(std::initializer_list<std::pair<const char*, const char*>> floats) {
    IntegratorSpec spec;
    spec.type = "sppm";
    spec.where = "scene.xml:3";
    int line = 4;
    for (const auto& [name, text] : floats) {
        IntegratorParam p;
        p.name = name;
        p.kind = IntegratorParam::Kind::Float;
        p.text = text;
        p.where = "scene.xml:" + std::to_string(line++);
        spec.params.push_back(p);
    }
    return spec;
}

std::string refusal(const IntegratorSpec& spec) {
    IntegratorParams params(spec);
    try {
        readSppmSettings(params);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SppmSettingsTest, DefaultsAndValues) {
    IntegratorParams none(sppmSpec({}));
    const SppmSettings d = readSppmSettings(none);
    EXPECT_EQ(d.photonCount, uint64_t(1) << 17);
    EXPECT_FLOAT_EQ(d.alpha, 2.0f / 3.0f);
    EXPECT_EQ(d.initialRadius, 0);
    EXPECT_EQ(d.path.maxDepth, -1);
    EXPECT_EQ(d.path.rrDepth, 5);
    IntegratorParams some(sppmSpec({{"alpha", "1"}, {"initial_radius", "0.25"}}));
    const SppmSettings s = readSppmSettings(some);
    EXPECT_EQ(s.alpha, 1.0f);
    EXPECT_EQ(s.initialRadius, 0.25f);
}

TEST(SppmSettingsTest, BadValuesAreRefusedWithFileLineAndReason) {
    EXPECT_EQ(refusal(sppmSpec({{"alpha", "0"}})), "scene.xml:4: integrator 'sppm': parameter 'alpha' must be in (0, 1]");
    EXPECT_EQ(refusal(sppmSpec({{"alpha", "1.5"}})),
              "scene.xml:4: integrator 'sppm': parameter 'alpha' must be in (0, 1]");
    EXPECT_EQ(refusal(sppmSpec({{"initial_radius", "-0.1"}})),
              "scene.xml:4: integrator 'sppm': parameter 'initial_radius' must be >= 0 (0: from the pixel footprint)");
    IntegratorSpec zero = sppmSpec({});
    zero.params.push_back({"photon_count", IntegratorParam::Kind::Integer, "0", "scene.xml:9"});
    EXPECT_EQ(refusal(zero),
              "scene.xml:9: integrator 'sppm': parameter 'photon_count' must be a whole number of photons in [1, 2^30]");
    // The command line's option names itself.
    IntegratorParams cli(sppmSpec({}), {{"alpha", IntegratorParam::Kind::Text, "-1", "--sppm-alpha"}});
    try {
        readSppmSettings(cli);
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "--sppm-alpha -1: must be in (0, 1]");
    }
}

// Knaus & Zwicker's global schedule: every pixel's radius follows R_{i+1}^2 = R_i^2 (i + a)/(i + 1),
// photons or none, and tau / (pi R^2) stays the sum of Phi_i / (pi R_i^2).
TEST(SppmUpdate, GlobalScheduleShrinksEveryPixelAndKeepsTheDensitySum) {
    SppmPixel p;
    p.radius = 2;
    const double phi1[3] = {4, 8, 0}, zero[3] = {0, 0, 0};
    const double kPi = 3.14159265358979323846;
    sppmUpdatePixelGlobal(p, phi1, 5, 0.5, 1);  // R^2: 4 -> 4 (1.5 / 2) = 3
    EXPECT_DOUBLE_EQ(p.radius * p.radius, 3.0);
    EXPECT_DOUBLE_EQ(p.tau[0] / (kPi * p.radius * p.radius), 4 / (kPi * 4));
    sppmUpdatePixelGlobal(p, zero, 0, 0.5, 2);  // no photons: shrinks all the same, R^2 = 3 (2.5 / 3) = 2.5
    EXPECT_DOUBLE_EQ(p.radius * p.radius, 2.5);
    EXPECT_DOUBLE_EQ(p.tau[1] / (kPi * p.radius * p.radius), 8 / (kPi * 4));
    const double phi3[3] = {3, 0, 0};
    sppmUpdatePixelGlobal(p, phi3, 1, 0.5, 3);  // R^2 = 2.5 (3.5 / 4)
    EXPECT_NEAR(p.radius * p.radius, 2.1875, 1e-12);
    EXPECT_NEAR(p.tau[0] / (kPi * p.radius * p.radius), 4 / (kPi * 4) + 3 / (kPi * 2.5), 1e-12);
    EXPECT_EQ(p.n, 6);
}

TEST(SppmSettingsTest, PhotonMapperChoicesAndTheirRefusals) {
    IntegratorSpec spec = sppmSpec({{"roughness_threshold", "0.2"}});
    spec.params.push_back({"radius_schedule", IntegratorParam::Kind::String, "global", "scene.xml:10"});
    spec.params.push_back({"structure", IntegratorParam::Kind::String, "grid", "scene.xml:11"});
    spec.params.push_back({"direction", IntegratorParam::Kind::String, "gather", "scene.xml:12"});
    spec.params.push_back({"max_passes", IntegratorParam::Kind::Integer, "7", "scene.xml:13"});
    spec.params.push_back({"photon_roulette", IntegratorParam::Kind::String, "throughput", "scene.xml:14"});
    IntegratorParams params(spec);
    const SppmSettings s = readSppmSettings(params);
    EXPECT_EQ(s.photonRoulette, PhotonRoulette::Throughput);
    IntegratorParams defaults(sppmSpec({}));
    EXPECT_EQ(readSppmSettings(defaults).photonRoulette, PhotonRoulette::Albedo);
    IntegratorParams defaultDirection(sppmSpec({}));
    EXPECT_EQ(readSppmSettings(defaultDirection).direction, PhotonDirection::Auto);
    EXPECT_EQ(s.radiusSchedule, RadiusSchedule::Global);
    EXPECT_EQ(s.structure, PhotonStructure::Grid);
    EXPECT_EQ(s.direction, PhotonDirection::Gather);
    EXPECT_EQ(s.maxPasses, 7u);
    EXPECT_FLOAT_EQ(s.roughnessThreshold, 0.2f);
    EXPECT_EQ(refusal(sppmSpec({{"roughness_threshold", "-1"}})),
              "scene.xml:4: integrator 'sppm': parameter 'roughness_threshold' must be in [0, 1] (a microfacet alpha)");
    IntegratorSpec bad = sppmSpec({});
    bad.params.push_back({"structure", IntegratorParam::Kind::String, "octree", "scene.xml:9"});
    EXPECT_NE(refusal(bad).find("scene.xml:9"), std::string::npos) << refusal(bad);
    IntegratorSpec badRoulette = sppmSpec({});
    badRoulette.params.push_back({"photon_roulette", IntegratorParam::Kind::String, "always", "scene.xml:9"});
    EXPECT_NE(refusal(badRoulette).find("scene.xml:9"), std::string::npos) << refusal(badRoulette);
    EXPECT_NE(refusal(badRoulette).find("albedo"), std::string::npos) << refusal(badRoulette);
    IntegratorSpec badDirection = sppmSpec({});
    badDirection.params.push_back({"direction", IntegratorParam::Kind::String, "both", "scene.xml:9"});
    EXPECT_NE(refusal(badDirection).find("scene.xml:9"), std::string::npos) << refusal(badDirection);
    EXPECT_NE(refusal(badDirection).find("auto"), std::string::npos) << refusal(badDirection);
    IntegratorSpec ppm = sppmSpec({});
    ppm.type = "ppm";
    ppm.params.push_back({"hitpoints", IntegratorParam::Kind::Integer, "0", "scene.xml:9"});
    IntegratorParams ppmParams(ppm);
    try {
        readSppmSettings(ppmParams, PhotonMapper::Ppm);
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "scene.xml:9: integrator 'ppm': parameter 'hitpoints' must be in [1, 256]");
    }
}

// Which vertices photon mapping treats as specular (no visible point, no deposit).
TEST(SppmSpecular, DeltaAlwaysRoughLobesBelowTheThreshold) {
    std::vector<Bsdf> bsdfs(4);
    bsdfs[0].type = BsdfType::Diffuse;
    bsdfs[1].type = BsdfType::Dielectric;
    bsdfs[2].type = BsdfType::RoughConductor;
    bsdfs[2].alphaU = bsdfs[2].alphaV = 0.15f;
    bsdfs[3].type = BsdfType::TwoSided;
    bsdfs[3].front = bsdfs[3].back = 2;
    const Span<const Bsdf> view(bsdfs.data(), bsdfs.size());
    EXPECT_FALSE(isSpecularBsdf(view, 0, 0.5f));
    EXPECT_TRUE(isSpecularBsdf(view, 1, 0));
    EXPECT_FALSE(isSpecularBsdf(view, 2, 0));
    EXPECT_FALSE(isSpecularBsdf(view, 2, 0.1f));
    EXPECT_TRUE(isSpecularBsdf(view, 2, 0.2f));
    EXPECT_TRUE(isSpecularBsdf(view, 3, 0.2f));
    EXPECT_FALSE(isSpecularBsdf(view, 3, 0.1f));
}

}  // namespace
}  // namespace caustica::test
