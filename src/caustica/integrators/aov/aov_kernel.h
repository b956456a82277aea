// aov_kernel.h — the values of the geometric AOVs (aov_layers.h) for one camera ray, as Mitsuba 3's
// aov integrator writes them (src/integrators/aov.cpp): the first hit's ray distance, position,
// uv, geometric and shading normals, diffuse albedo, primitive and shape index; on a miss every
// channel is 0 (Mitsuba zeroes the interaction). Single source (CA_HD).
#pragma once

#include "caustica/film/aov_layers.h"
#include "caustica/scene/bsdf.h"
#include "caustica/scene/interaction.h"

namespace caustica {

/// The layers the AOV pass computes (variance is the session's, not a ray's): a fixed array, so
/// kernels take it by value.
struct AovLayout {
    int count = 0;     // layers
    int channels = 0;  // their channels in all
    AovType types[kMaxAovLayers] = {};
};

/// The layout of `spec`'s geometric layers (all but variance), in spec order.
inline AovLayout aovLayout(const AovSpec& spec) {
    AovLayout layout;
    for (const AovLayer& l : spec.layers) {
        if (l.type == AovType::Variance) continue;
        layout.types[layout.count++] = l.type;
        layout.channels += aovChannelCount(l.type);
    }
    return layout;
}

/// Mitsuba's eval_diffuse_reflectance at `si` seen from `wo`: twosided, bumpmap and normalmap
/// resolved to the child on the viewer's side; diffuse: its reflectance, plastic and
/// roughplastic: their diffuse_reflectance (textures evaluated at si.uv); any other BSDF the
/// base class's approximation, f(wo, n) |cos| π with n the shading normal.
CA_HD_INLINE Spectrum aovAlbedo(const SceneView& view, const SurfaceInteraction& si, Vec3f wo) {
    const uint32_t id = view.shapes[si.shape].bsdf;
    const bsdf_detail::Resolved r = bsdf_detail::resolve(view.bsdfs, id, si, wo);
    bsdf_detail::BsdfScratch scratch;
    const Bsdf& b = bsdf_detail::applyBsdfTextures(*r.bsdf, si, scratch);
    if (b.type == BsdfType::Diffuse) return b.reflectance;
    if (b.type == BsdfType::Plastic || b.type == BsdfType::RoughPlastic) return b.diffuse;
    return evalBsdf(view.bsdfs, id, si, wo, r.frame.n) * kPi;
}

/// Index of the hit primitive inside its own shape (Mitsuba's si.prim_index): a mesh's triangle,
/// 0 for a sphere or cylinder.
CA_HD_INLINE uint32_t aovPrimIndex(const SceneView& view, const SurfaceInteraction& si) {
    const Shape& shape = view.shapes[si.shape];
    return shape.type == ShapeType::Mesh ? si.primId - shape.primOffset : 0u;
}

/// Writes layout.channels values for camera ray `ray` and its closest hit (`hit` invalid: a
/// miss) to out[0 .. layout.channels).
CA_HD_INLINE void aovValues(const SceneView& view, const Ray& ray, const Hit& hit,
                            const AovLayout& layout, float* out) {
    if (!hit.valid()) {
        for (int c = 0; c < layout.channels; ++c) out[c] = 0;
        return;
    }
    const SurfaceInteraction si = computeInteraction(view, ray, hit, true);  // the uv AOV reads uv
    for (int i = 0; i < layout.count; ++i) {
        switch (layout.types[i]) {
            case AovType::Depth:
                *out++ = hit.t;
                break;
            case AovType::Position:
                *out++ = si.p.x;
                *out++ = si.p.y;
                *out++ = si.p.z;
                break;
            case AovType::Uv:
                *out++ = si.uv.x;
                *out++ = si.uv.y;
                break;
            case AovType::GeoNormal:
                *out++ = si.ng.x;
                *out++ = si.ng.y;
                *out++ = si.ng.z;
                break;
            case AovType::ShNormal:
                *out++ = si.ns.x;
                *out++ = si.ns.y;
                *out++ = si.ns.z;
                break;
            case AovType::Albedo: {
                const Spectrum a = aovAlbedo(view, si, -ray.d);
                *out++ = a.r;
                *out++ = a.g;
                *out++ = a.b;
                break;
            }
            case AovType::PrimIndex:
                *out++ = Float(aovPrimIndex(view, si));
                break;
            case AovType::ShapeIndex:
                *out++ = Float(si.shape + 1);
                break;
            default:
                break;  // Variance: not in a layout
        }
    }
}

}  // namespace caustica
