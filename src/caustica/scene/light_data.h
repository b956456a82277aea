// light_data.h — the closed list of emitters as one tagged record. Functions live in light.h.
#pragma once

#include <cstdint>

#include "caustica/util/spectrum.h"

namespace caustica {

enum class LightType : uint32_t {
    Area,      // diffuse area emitter on a shape: constant radiance on the front side
    Point,     // isotropic point light (intensity, W/sr)
    Constant,  // uniform environment radiance from every direction
};

struct Light {
    LightType type = LightType::Area;
    Spectrum radiance;        // area, constant: radiance; point: intensity
    Vec3f position;           // point light position
    uint32_t shape = 0;       // area: emitting shape (index into SceneView::shapes)
    uint32_t cdfOffset = 0;   // area light on a mesh: its triangles' normalised cumulative areas
    uint32_t cdfCount = 0;    //   are SceneView::lightCdf[cdfOffset, cdfOffset + cdfCount)
    Float area = 0;           // area: total surface area of the shape
    Vec3f sceneCenter;        // constant: bounding sphere of the scene (for sampling/power)
    Float sceneRadius = 0;
};

}  // namespace caustica
