// bsdf_data.h — the closed list of BSDFs as one tagged record (no virtual calls in kernels).
// Functions over it live in bsdf.h.
#pragma once

#include <cstdint>

#include "caustica/util/spectrum.h"

namespace caustica {

enum class BsdfType : uint32_t {
    Diffuse,         // Lambertian; one-sided (black from the back) like Mitsuba's diffuse
    Dielectric,      // smooth glass/water interface, Fresnel-weighted reflection + refraction
    Conductor,       // smooth metal, complex-IOR Fresnel; one-sided
    RoughConductor,  // GGX microfacet metal (visible-normal sampling); one-sided
    TwoSided,        // Mitsuba's twosided: `front` on the front, `back` (mirrored) on the back
};

struct Bsdf {
    BsdfType type = BsdfType::Diffuse;
    Spectrum reflectance{0.5f};            // diffuse reflectance / specular_reflectance
    Spectrum transmittance{1.0f};          // dielectric specular_transmittance
    Spectrum eta{0.0f}, k{0.0f};           // conductor complex IOR relative to the exterior
    Float etaRatio = 1.5046f;              // dielectric int_ior / ext_ior
    Float alphaU = 0.1f, alphaV = 0.1f;    // rough conductor GGX roughness
    uint32_t front = 0, back = 0;          // twosided: indices of the two child BSDFs
};

}  // namespace caustica
