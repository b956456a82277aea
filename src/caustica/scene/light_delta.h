// light_delta.h — the delta emitters besides the point light, as Mitsuba 3 defines them (shared
// CPU/GPU code used by sampleLight in light.h).
//
//   spot         intensity I at `position`, shining along to_world's +z. Mitsuba 3's falloff
//                (src/emitters/spot.cpp): 1 inside beam_width, then linear in the angle θ
//                down to 0 at cutoff_angle: (cutoff − θ) / (cutoff − beam_width); times an
//                optional texture at uv = 0.5 + 0.5 (x, y) / (z tan(cutoff)) of the local
//                direction (Mitsuba's direction_to_uv).
//   directional  irradiance E arriving along `direction` from outside the scene's bounding
//                sphere (src/emitters/directional.cpp); the shadow ray is unbounded.
#pragma once

#include "caustica/scene/light_data.h"
#include "caustica/scene/texture.h"
#include "caustica/util/math.h"

namespace caustica {

/// Rows `m` applied to v (a 3x3 linear map stored as three row vectors).
CA_HD_INLINE Vec3f applyRows(const Vec3f (&m)[3], Vec3f v) {
    return {dot(m[0], v), dot(m[1], v), dot(m[2], v)};
}

/// The spot light's falloff towards local direction `local` (any length; +z is the axis).
CA_HD_INLINE Float spotFalloff(const Light& light, Vec3f local) {
    const Float len = length(local);
    if (!(len > 0)) return 0;
    const Float cosTheta = local.z / len;
    if (!(cosTheta > light.cosCutoff)) return 0;
    if (cosTheta >= light.cosBeam) return 1;
    const Float theta = std::acos(min(cosTheta, Float(1)));
    return max(Float(0), (light.cutoff - theta) * light.invTransition);
}

/// Intensity the spot sends from its position towards world direction `w` (unit, away from it).
CA_HD_INLINE Spectrum spotIntensity(const Light& light, const TextureView& textures, Vec3f w) {
    const Vec3f local = applyRows(light.localFromWorld, w);
    const Float falloff = spotFalloff(light, local);
    if (light.texture == kNoTexture || !(falloff > 0)) return light.radiance * falloff;
    const Float zf = local.z * light.uvFactor;
    const Vec2f uv(Float(0.5) + Float(0.5) * local.x / zf, Float(0.5) + Float(0.5) * local.y / zf);
    return light.radiance * evalTexture(textures, light.texture, uv) * falloff;
}

}  // namespace caustica
