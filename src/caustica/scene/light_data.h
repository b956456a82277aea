// light_data.h — the closed list of emitters as one tagged record. Functions live in light.h.
#pragma once

#include <cstdint>

#include "caustica/scene/texture.h"
#include "caustica/util/spectrum.h"

namespace caustica {

enum class LightType : uint32_t {
    Area,      // diffuse area emitter on a shape: constant radiance on the front side
    Point,     // isotropic point light (intensity, W/sr)
    Constant,  // uniform environment radiance from every direction
    Spot,         // point light in a cone with Mitsuba 3's linear falloff (light_delta.h)
    Directional,  // distant light: irradiance along one direction (light_delta.h)
    EnvMap,       // lat-long environment map, importance-sampled (light_envmap.h)
};

struct Light {
    LightType type = LightType::Area;
    Spectrum radiance;        // area, constant: radiance; point: intensity
    Vec3f position;           // point light position
    uint32_t shape = 0;       // area: emitting shape (index into SceneView::shapes)
    uint32_t cdfOffset = 0;   // area light on a mesh: its triangles' normalised cumulative areas
    uint32_t cdfCount = 0;    //   are SceneView::lightCdf[cdfOffset, cdfOffset + cdfCount)
    Float area = 0;           // area: total surface area of the shape
    // Area light on a mesh of two triangles that form a parallelogram (a rectangle shape): its
    // points are quadCorner + s quadEdgeU + t quadEdgeV, (s, t) in [0, 1)², uniform by area
    // without the triangle CDF, and quadNormal is its front unit normal (light_setup.cpp).
    bool isQuad = false;
    Vec3f quadCorner, quadEdgeU, quadEdgeV, quadNormal;
    Vec3f sceneCenter;        // constant, directional, envmap: bounding sphere of the scene
    Float sceneRadius = 0;
    // spot: intensity in `radiance`, position in `position`; directional: irradiance in
    // `radiance`; envmap: `radiance` is the scale (already applied to the texels), black when
    // the whole map is black (nothing to sample).
    Vec3f localFromWorld[3];  // spot, envmap: rows of the inverse of to_world's linear part
    Vec3f worldFromLocal[3];  // envmap: rows of to_world's linear part
    Vec3f direction;          // directional: unit direction the light travels
    Float cosCutoff = 0, cosBeam = 1, cutoff = 0, invTransition = 0;  // spot (radians)
    uint32_t texture = kNoTexture;  // spot: `texture` (SceneView::textures), or none
    Float uvFactor = 0;             // spot: tan(cutoff), maps directions to the texture's uv
    uint32_t texOffset = 0;   // envmap: texels SceneView::lightTexels[texOffset, + w * h),
    uint32_t texWidth = 0, texHeight = 0;  // row-major from the top row; its sampling CDFs
                              // are SceneView::lightCdf[cdfOffset, cdfOffset + cdfCount)
};

}  // namespace caustica
