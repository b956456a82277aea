// light_envmap_setup.h — builds an envmap emitter's sampling distribution on the host (see
// light_envmap.h for the distribution it describes).
#pragma once

#include "caustica/scene/scene.h"

namespace caustica {

/// Appends the marginal (H − 1 rows) and conditional (W patches per row) CDFs of `light`'s
/// texels (Scene::lightTexels[texOffset, + W·H)) to scene.lightCdf and sets light.cdfOffset /
/// cdfCount. Throws caustica::Error for a map smaller than 2x3 texels or texels out of range.
void setupEnvMapDistribution(Scene& scene, Light& light);

}  // namespace caustica
