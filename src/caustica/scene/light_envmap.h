// light_envmap.h — Mitsuba 3's `envmap` emitter: evaluation and importance sampling of a
// latitude-longitude radiance map (shared CPU/GPU code; the distribution is built on the host by
// light_envmap_setup.h).
//
// Mapping (Mitsuba 3, src/emitters/envmap.cpp): a local direction d = (sinφ sinθ, cosθ,
// −cosφ sinθ) has uv = (φ / 2π, θ / π): +y is up (the top row), the image's centre column
// looks along +z and its left and right edges along −z. The map is interpolated bilinearly with texel centres at
// u = (x + ½) / W (wrapping around in u) and v = y / (H − 1) (the first and last rows lie on the
// poles).
//
// Sampling: a 2-D piecewise-constant distribution over the (W) × (H − 1) bilinear patches
// (patch (i, j) spans texels i, i+1 and rows j, j+1), each weighted by the mean luminance of its
// four texels times the mean of sinθ over its rows: a marginal CDF over rows, then a CDF over the
// patches of the chosen row, then a uniform point in the patch (pbrt-v3 §14.2.4). With
// p(u, v) the density in the unit square, the solid-angle density is p / (2π² sinθ). Patches
// whose four texels are black have zero probability, where the radiance is zero as well.
#pragma once

#include "caustica/scene/light_delta.h"
#include "caustica/scene/scene.h"
#include "caustica/util/sampling.h"

namespace caustica {

namespace envmap_detail {

/// Mitsuba's direction_to_uv for a unit local direction.
CA_HD_INLINE Vec2f directionToUv(Vec3f d) {
    Float u = std::atan2(d.x, -d.z) * kInv2Pi;
    u -= std::floor(u);
    const Float v = std::acos(clamp(d.y, Float(-1), Float(1))) * kInvPi;
    return {u, v};
}

/// Inverse of directionToUv.
CA_HD_INLINE Vec3f uvToDirection(Vec2f uv, Float& sinTheta) {
    const Float theta = uv.y * kPi, phi = uv.x * (2 * kPi);
    sinTheta = std::sin(theta);
    return {std::sin(phi) * sinTheta, std::cos(theta), -std::cos(phi) * sinTheta};
}

/// Patch-grid coordinates (s in [0, W), t in [0, H − 1]) of uv: texel x's centre is at s = x.
CA_HD_INLINE Vec2f uvToGrid(const Light& l, Vec2f uv) {
    Float s = uv.x * Float(l.texWidth) - Float(0.5);
    if (s < 0) s += Float(l.texWidth);
    return {s, uv.y * Float(l.texHeight - 1)};
}

CA_HD_INLINE Span<const float> marginalCdf(const SceneView& scene, const Light& l) {
    return Span<const float>(scene.lightCdf.data() + l.cdfOffset, l.texHeight - 1);
}

CA_HD_INLINE Span<const float> rowCdf(const SceneView& scene, const Light& l, uint32_t row) {
    return Span<const float>(scene.lightCdf.data() + l.cdfOffset + (l.texHeight - 1) +
                                 size_t(row) * l.texWidth,
                             l.texWidth);
}

}  // namespace envmap_detail

/// Radiance the map sends towards the scene along -w, for world direction `w` pointing away from
/// the scene (bilinear, as Mitsuba's eval; the scale is already in the texels).
CA_HD_INLINE Spectrum envMapRadiance(const SceneView& scene, const Light& l, Vec3f w) {
    using namespace envmap_detail;
    const Vec3f local = normalize(applyRows(l.localFromWorld, w));
    const Vec2f g = uvToGrid(l, directionToUv(local));
    const uint32_t W = l.texWidth, H = l.texHeight;
    const uint32_t x0 = min(uint32_t(g.x), W - 1), y0 = min(uint32_t(g.y), H - 2);
    const uint32_t x1 = x0 + 1 == W ? 0 : x0 + 1;
    const Float fx = g.x - Float(x0), fy = g.y - Float(y0);
    const Spectrum* t = scene.lightTexels.data() + l.texOffset;
    const Spectrum top = t[y0 * W + x0] * (1 - fx) + t[y0 * W + x1] * fx;
    const Spectrum bottom = t[(y0 + 1) * W + x0] * (1 - fx) + t[(y0 + 1) * W + x1] * fx;
    return top * (1 - fy) + bottom * fy;
}

/// Solid-angle density (without light selection) with which envMapSample picks world direction
/// `w` (unit, away from the scene).
CA_HD_INLINE Float envMapPdf(const SceneView& scene, const Light& l, Vec3f w) {
    using namespace envmap_detail;
    if (l.radiance.isBlack()) return 0;  // a black map (light_envmap_setup.cpp)
    const Vec3f local = normalize(applyRows(l.localFromWorld, w));
    const Float sinTheta = std::sqrt(local.x * local.x + local.z * local.z);
    if (!(sinTheta > 0)) return 0;
    const Vec2f g = uvToGrid(l, directionToUv(local));
    const uint32_t i = min(uint32_t(g.x), l.texWidth - 1), j = min(uint32_t(g.y), l.texHeight - 2);
    const Float p = discreteCdfPmf(marginalCdf(scene, l), j) * discreteCdfPmf(rowCdf(scene, l, j), i);
    return p * Float(l.texWidth) * Float(l.texHeight - 1) / (2 * kPi * kPi * sinTheta);
}

/// Samples a world direction `w` (away from the scene) with density `pdf` (solid angle, without
/// light selection). False when the map is black or the sample lands on a pole.
CA_HD_INLINE bool envMapSample(const SceneView& scene, const Light& l, Vec2f u, Vec3f& w,
                               Float& pdf) {
    using namespace envmap_detail;
    if (l.radiance.isBlack()) return false;  // a black map (light_envmap_setup.cpp)
    const Span<const float> marginal = marginalCdf(scene, l);
    Float pRow, pCol;
    const uint32_t j = sampleDiscreteCdf(marginal, u.y, &pRow);
    if (!(pRow > 0)) return false;
    const Float ty = min((u.y - (j > 0 ? marginal[j - 1] : 0.0f)) / pRow, kOneMinusEpsilon);
    const Span<const float> row = rowCdf(scene, l, j);
    const uint32_t i = sampleDiscreteCdf(row, u.x, &pCol);
    if (!(pCol > 0)) return false;
    const Float tx = min((u.x - (i > 0 ? row[i - 1] : 0.0f)) / pCol, kOneMinusEpsilon);
    // Grid position -> uv (undoing uvToGrid's half-texel shift, wrapping in u).
    Float uu = (Float(i) + max(tx, Float(0)) + Float(0.5)) / Float(l.texWidth);
    if (uu >= 1) uu -= 1;
    const Float vv = (Float(j) + max(ty, Float(0))) / Float(l.texHeight - 1);
    Float sinTheta;
    Vec3f local = uvToDirection(Vec2f(uu, vv), sinTheta);
    w = normalize(applyRows(l.worldFromLocal, local));
    // sinθ of the direction itself, as envMapPdf computes it (precise near the poles).
    local = normalize(applyRows(l.localFromWorld, w));
    sinTheta = std::sqrt(local.x * local.x + local.z * local.z);
    if (!(sinTheta > 0)) return false;
    pdf = pRow * pCol * Float(l.texWidth) * Float(l.texHeight - 1) / (2 * kPi * kPi * sinTheta);
    return pdf > 0 && std::isfinite(pdf);
}

}  // namespace caustica
