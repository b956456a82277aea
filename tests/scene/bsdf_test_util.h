// bsdf_test_util.h — small builders shared by the BSDF tests (test helper, host only).
#pragma once

#include <cmath>
#include <vector>

#include "caustica/scene/bsdf.h"

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

/// |a - b| within a relative tolerance (with a tiny absolute floor for values near zero).
inline bool relClose(double a, double b, double rel = 1e-3, double absFloor = 1e-6) {
    return std::fabs(a - b) <= rel * std::max(std::fabs(a), std::fabs(b)) + absFloor;
}

}  // namespace caustica::test
