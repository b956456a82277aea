// bsdf_test_util.h — small builders, the comparison with Mitsuba's values and the χ² sampling
// harness shared by the BSDF tests (test helper, host only).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/util/rng.h"
#include "scene/chi2.h"

namespace caustica::test {

/// A unit direction from spherical angles in degrees, in the frame of normal `n`.
inline Vec3f directionDeg(Frame frame, double thetaDeg, double phiDeg) {
    const double t = thetaDeg * M_PI / 180, p = phiDeg * M_PI / 180;
    return normalize(frame.toWorld(Vec3f(Float(std::sin(t) * std::cos(p)),
                                         Float(std::sin(t) * std::sin(p)), Float(std::cos(t)))));
}

/// A surface point at the origin with geometric and shading normal `n`.
inline SurfaceInteraction surfaceAt(Vec3f n) {
    SurfaceInteraction si;
    si.p = Vec3f(0);
    si.ng = si.ns = normalize(n);
    si.primId = 0;
    return si;
}

inline Bsdf diffuse(Spectrum r) {
    Bsdf b;
    b.type = BsdfType::Diffuse;
    b.reflectance = r;
    return b;
}

inline Bsdf roughConductor(Float au, Float av, Spectrum eta = Spectrum(0.f),
                           Spectrum k = Spectrum(1.f), Spectrum r = Spectrum(1.f)) {
    Bsdf b;
    b.type = BsdfType::RoughConductor;
    b.alphaU = au;
    b.alphaV = av;
    b.eta = eta;
    b.k = k;
    b.reflectance = r;
    return b;
}

/// A rough conductor with Mitsuba's default distribution, Beckmann.
inline Bsdf beckmannConductor(Float au, Float av, Spectrum eta = Spectrum(0.f),
                              Spectrum k = Spectrum(1.f), Spectrum r = Spectrum(1.f)) {
    Bsdf b = roughConductor(au, av, eta, k, r);
    b.distribution = MicrofacetType::Beckmann;
    return b;
}

inline Bsdf plastic(Float etaRatio = 1.49f, Spectrum diffuse = Spectrum(0.5f),
                    Spectrum specular = Spectrum(1.f), bool nonlinear = false) {
    return makePlastic(etaRatio, diffuse, specular, nonlinear);
}

inline Bsdf conductor(Spectrum eta, Spectrum k, Spectrum r = Spectrum(1.f)) {
    Bsdf b;
    b.type = BsdfType::Conductor;
    b.eta = eta;
    b.k = k;
    b.reflectance = r;
    return b;
}

inline Bsdf dielectric(Float etaRatio, Spectrum r = Spectrum(1.f), Spectrum t = Spectrum(1.f)) {
    Bsdf b;
    b.type = BsdfType::Dielectric;
    b.etaRatio = etaRatio;
    b.reflectance = r;
    b.transmittance = t;
    return b;
}

inline Bsdf roughDielectric(Float etaRatio, Float au, Float av,
                            MicrofacetType type = MicrofacetType::Beckmann,
                            Spectrum r = Spectrum(1.f), Spectrum t = Spectrum(1.f)) {
    Bsdf b = dielectric(etaRatio, r, t);
    b.type = BsdfType::RoughDielectric;
    b.distribution = type;
    b.alphaU = au;
    b.alphaV = av;
    return b;
}

inline Bsdf thinDielectric(Float etaRatio, Spectrum r = Spectrum(1.f), Spectrum t = Spectrum(1.f)) {
    Bsdf b = dielectric(etaRatio, r, t);
    b.type = BsdfType::ThinDielectric;
    return b;
}

/// Appends twosided(front, back) to `bsdfs` (children first) and returns its index.
inline uint32_t addTwoSided(std::vector<Bsdf>& bsdfs, const Bsdf& front, const Bsdf& back) {
    bsdfs.push_back(front);
    bsdfs.push_back(back);
    Bsdf t;
    t.type = BsdfType::TwoSided;
    t.front = uint32_t(bsdfs.size() - 2);
    t.back = uint32_t(bsdfs.size() - 1);
    bsdfs.push_back(t);
    return uint32_t(bsdfs.size() - 1);
}

/// A bumpmap or normalmap adapter around bsdfs[nested], its frame read from texture `texture`
/// (`scale`: the bump height's scale).
inline Bsdf frameAdapter(BsdfType type, uint32_t nested, uint32_t texture, Float scale = 1) {
    Bsdf b;
    b.type = type;
    b.front = nested;
    b.frameTexture = texture;
    b.bumpScale = scale;
    return b;
}

/// |a - b| within a relative tolerance (with a tiny absolute floor for values near zero).
inline bool relClose(double a, double b, double rel = 1e-3, double absFloor = 1e-6) {
    return std::fabs(a - b) <= rel * std::max(std::fabs(a), std::fabs(b)) + absFloor;
}

/// A value of Mitsuba's eval and pdf (python: bsdf.eval / bsdf.pdf), directions in degrees (θ, φ)
/// of si.wi (our wo) and wo (our wi).
struct MitsubaValue {
    double thetaO, phiO, thetaI, phiI;
    Spectrum f;
    double pdf;
};

/// Checks evalBsdf and pdfBsdf of `b` (at a surface with normal +z) against Mitsuba's `values`
/// within the relative tolerance `tol` (relClose).
inline void expectMatchesMitsuba(const Bsdf& b, const std::vector<MitsubaValue>& values,
                                 double tol = 1e-3) {
    const std::vector<Bsdf> bsdfs{b};
    const SurfaceInteraction si = surfaceAt({0, 0, 1});
    const Frame frame(si.ns);
    for (const MitsubaValue& v : values) {
        const Vec3f wo = directionDeg(frame, v.thetaO, v.phiO);
        const Vec3f wi = directionDeg(frame, v.thetaI, v.phiI);
        const Spectrum f = evalBsdf(bsdfs, 0, si, wo, wi);
        for (int c = 0; c < 3; ++c)
            EXPECT_TRUE(relClose(f[c], v.f[c], tol))
                << "θo " << v.thetaO << " θi " << v.thetaI << ": " << f[c] << " vs " << v.f[c];
        const Float pdf = pdfBsdf(bsdfs, 0, si, wo, wi);
        EXPECT_TRUE(relClose(pdf, v.pdf, tol))
            << "pdf θo " << v.thetaO << " θi " << v.thetaI << ": " << pdf << " vs " << v.pdf;
    }
}

/// Samples per BSDF χ² test.
inline constexpr int kBsdfChi2Samples = 1000000;

/// One χ² case of a BSDF seen from a fixed direction: bsdfs[id] at a surface point with shading
/// normal n, viewed along wo at (thetaO, phiO) degrees in the frame of n.
struct BsdfChi2Case {
    std::string name;
    std::vector<Bsdf> bsdfs;
    uint32_t id = 0;
    Vec3f n{0, 0, 1};             // shading normal
    double thetaO = 0, phiO = 0;  // viewing direction wo in degrees, in the frame of n
    int nTheta = 64, nPhi = 128;  // histogram resolution
    int k = 4;                    // Simpson subintervals per bin and axis (checked against 2k)
};

inline void PrintTo(const BsdfChi2Case& c, std::ostream* os) { *os << c.name; }

/// The surface point, viewing direction and histogram grid of a BsdfChi2Case.
struct BsdfChi2View {
    SurfaceInteraction si;
    Vec3f wo;
    SphereGrid grid;

    explicit BsdfChi2View(const BsdfChi2Case& c) : si(surfaceAt(c.n)) {
        grid.frame = Frame(si.ns);
        grid.nTheta = c.nTheta;
        grid.nPhi = c.nPhi;
        wo = directionDeg(grid.frame, c.thetaO, c.phiO);
    }
};

/// Sample i of sampleBsdf(bsdfs, id, si, wo), its numbers (uLobe, then u) drawn from
/// IndependentSampler(i, 0, seed).
inline bool sampleBsdfAt(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                         Vec3f wo, int i, uint64_t seed, BsdfSample& bs) {
    IndependentSampler rng(uint64_t(i), 0, seed);
    const Float uLobe = rng.get1D();
    const Vec2f u = rng.get2D();
    return sampleBsdf(bsdfs, id, si, wo, uLobe, u, bs);
}

/// χ² test (chi2Directions, k Simpson subintervals) of kBsdfChi2Samples directions drawn by
/// sampleBsdfAt(sampled, ...) against pdfBsdf(claimed, id, si, wo) on `grid`. `keep` sees every
/// sample drawn and says whether its direction enters the histogram (else it counts as none).
inline Chi2Result bsdfChi2(Span<const Bsdf> sampled, Span<const Bsdf> claimed, uint32_t id,
                           const SurfaceInteraction& si, Vec3f wo, const SphereGrid& grid,
                           uint64_t seed, int k = 4,
                           const std::function<bool(const BsdfSample&)>& keep = {}) {
    auto sample = [&](int i, Vec3f& w) {
        BsdfSample bs;
        if (!sampleBsdfAt(sampled, id, si, wo, i, seed, bs) || (keep && !keep(bs))) return false;
        w = bs.wi;
        return true;
    };
    auto pdf = [&](Vec3f w) { return double(pdfBsdf(claimed, id, si, wo, w)); };
    return chi2Directions(grid, kBsdfChi2Samples, sample, pdf, k);
}

/// The mirror of wo about the shading normal (the direction of a specular reflection).
inline Vec3f mirrorOf(const SurfaceInteraction& si, Vec3f wo) {
    return si.ns * (2 * dot(wo, si.ns)) - wo;
}

/// Per-sample consistency of smooth BSDF samples with evalBsdf / pdfBsdf (relClose): counts those
/// whose pdf differs from pdfBsdf and those whose weight differs from f / pdf in some channel,
/// describing the first of the latter.
struct BsdfSampleCheck {
    int badWeight = 0, badPdf = 0;
    std::string firstBad;

    void check(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si, Vec3f wo,
               const BsdfSample& bs) {
        const Spectrum f = evalBsdf(bsdfs, id, si, wo, bs.wi);
        const Float pdf = pdfBsdf(bsdfs, id, si, wo, bs.wi);
        if (!relClose(bs.pdf, pdf)) ++badPdf;
        for (int ch = 0; ch < 3; ++ch)
            if (!(pdf > 0) || !relClose(bs.weight[ch], f[ch] / pdf)) {
                if (badWeight++ == 0)
                    firstBad = "weight " + std::to_string(bs.weight[ch]) + " vs f/pdf " +
                               std::to_string(f[ch] / pdf);
                break;
            }
    }
};

}  // namespace caustica::test
