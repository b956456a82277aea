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
    RoughPlastic,    // Mitsuba's roughplastic: diffuse base under a rough coating (bsdf_rough_plastic.h)
    Blend,           // Mitsuba's blendbsdf: (1 - weight) `front` + weight `back` (bsdf_composite.h)
    Mask,            // Mitsuba's mask: `front` with probability `weight`, else passes straight on
    Null,            // Mitsuba's null: an invisible interface (straight pass-through)
    BumpMap,         // Mitsuba's bumpmap: `front` under a frame tilted by a height texture's gradient
    NormalMap,       // Mitsuba's normalmap: `front` under a frame from a tangent-space normal texture
    Principled,      // Mitsuba's principled (Disney 2015): bsdf_principled.h
};

/// A Bsdf field that a texture may replace (see texture.h and applyBsdfTextures in bsdf.h).
enum class BsdfParam : uint32_t {
    Reflectance,    // reflectance / specular_reflectance
    Diffuse,        // plastic diffuse_reflectance
    Transmittance,  // specular_transmittance
    Alpha,          // alpha: alphaU and alphaV
    AlphaU,
    AlphaV,
    Weight,         // blendbsdf weight / mask opacity
    Eta,            // conductor eta
    K,              // conductor k
    // principled weights (PrincipledParams)
    Roughness,
    Anisotropic,
    Metallic,
    SpecTint,
    Sheen,
    SheenTint,
    Clearcoat,
    ClearcoatGloss,
    SpecTrans,
    Flatness,
};

/// One textured parameter: `param` takes the value of texture `texture` at si.uv.
struct BsdfTexture {
    BsdfParam param = BsdfParam::Reflectance;
    uint32_t texture = 0;
};
/// Textured parameters per Bsdf record: principled has the most (base_color and ten weights).
constexpr int kMaxBsdfTextures = 12;

/// Entries of roughplastic's table of the coating's external transmittance over cosθ.
constexpr int kRoughPlasticTableSize = 64;

/// Mitsuba's principled parameters (base_color is Bsdf::reflectance); the `has` flags are
/// Mitsuba's m_has_*: a lobe is evaluated only when its parameter was given (and not 0).
struct PrincipledParams {
    Float roughness = 0.5f, anisotropic = 0, metallic = 0, specTint = 0, sheen = 0,
          sheenTint = 0, clearcoat = 0, clearcoatGloss = 0, specTrans = 0, flatness = 0;
    Float eta = 1.5f;  // from `eta`, or 2 / (1 - sqrt(0.08 specular)) - 1
    Float specRate = 1, clearcoatRate = 1, diffuseRate = 1;  // sampling rates
    bool hasAnisotropic = false, hasMetallic = false, hasSpecTint = false, hasSheen = false,
         hasSheenTint = false, hasClearcoat = false, hasSpecTrans = false, hasFlatness = false;
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
    uint32_t front = 0, back = 0;          // twosided: the two children; blendbsdf: bsdf_0, bsdf_1;
                                           // mask: the nested bsdf in `front`
    Float weight = 0.5f;                   // blendbsdf weight / mask opacity, in [0, 1]
    // roughplastic: external transmittance 1 - R(cosθ) of the rough coating at cosθ = i/63
    // (Mitsuba's table, makeRoughPlastic); the internal reflectance is in fdrInt
    Float roughTransmittance[kRoughPlasticTableSize] = {};
    // textured parameters, applied before evaluation (applyBsdfTextures in bsdf.h)
    BsdfTexture textures[kMaxBsdfTextures] = {};
    uint32_t numTextures = 0;
    // bumpmap / normalmap (nested bsdf in `front`): the height or normal texture, bump scale
    uint32_t frameTexture = 0;
    Float bumpScale = 1;
    bool flipInvalidNormals = true;  // flip_invalid_normals
    bool shadowTerminator = true;    // use_shadowing_function
    PrincipledParams principled;           // principled (base_color in `reflectance`)
};

}  // namespace caustica
