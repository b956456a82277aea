// light_setup.h — derived light data computed once after a scene is built (host only).
#pragma once

#include "caustica/scene/scene.h"

namespace caustica {

/// Fills what light sampling needs: per-area-light triangle CDFs (Light::cdfOffset/cdfCount and
/// Scene::lightCdf), Light::area, the constant emitter's scene bounding sphere, and
/// Scene::environmentLight. Call after all shapes and lights are in the scene.
void finalizeLights(Scene& scene);

}  // namespace caustica
