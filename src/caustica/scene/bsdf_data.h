// bsdf_data.h — the closed list of BSDFs as one tagged record (no virtual calls in kernels).
// Functions over it live in bsdf.h.
#pragma once

#include <cstdint>

#include "caustica/scene/microfacet.h"
#include "caustica/util/spectrum.h"

namespace caustica {

enum class BsdfType : uint32_t {
    Diffuse,         // Lambertian; one-sided (black from the back) like Mitsuba's diffuse
    Dielectric,      // smooth glass/water interface, Fresnel-weighted reflection + refraction
    Conductor,       // smooth metal, complex-IOR Fresnel; one-sided
    RoughConductor,  // Beckmann or GGX microfacet metal (visible-normal sampling); one-sided
    RoughDielectric, // Beckmann or GGX microfacet interface between dielectrics (Walter et al. 2007)
    ThinDielectric,  // Mitsuba's thindielectric: a thin pane, reflection or straight pass-through
    Plastic,         // Mitsuba's plastic: diffuse base under a smooth dielectric coating; one-sided
    TwoSided,        // Mitsuba's twosided: `front` on the front, `back` (mirrored) on the back
};

struct Bsdf {
    BsdfType type = BsdfType::Diffuse;
    Spectrum reflectance{0.5f};            // diffuse reflectance / specular_reflectance
    Spectrum diffuse{0.5f};                // plastic diffuse_reflectance
    Spectrum transmittance{1.0f};          // (rough, thin) dielectric specular_transmittance
    Spectrum eta{0.0f}, k{0.0f};           // conductor complex IOR relative to the exterior
    Float etaRatio = 1.5046f;              // (rough, thin) dielectric, plastic: int_ior / ext_ior
    MicrofacetType distribution = MicrofacetType::GGX;  // rough conductor / dielectric
    Float alphaU = 0.1f, alphaV = 0.1f;    // rough conductor / dielectric roughness
    // plastic: Mitsuba's precomputed terms (see makePlastic in bsdf.h)
    Float fdrInt = 0;                      // diffuse Fresnel reflectance of the coating from inside
    Float specularWeight = 0.5f;           // probability weight of the specular lobe
    bool nonlinear = false;                // plastic: colour shift by internal scattering
    uint32_t front = 0, back = 0;          // twosided: indices of the two child BSDFs
};

}  // namespace caustica
