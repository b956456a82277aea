// hit_prefetch.h — prefetches of what computeInteraction will read for a hit, for the loops that
// take many hits in a row (the wavefront's shade stage, the photon pass's packets): a CPU starts
// the loads of later hits while it shades the current one. Nothing on a GPU (prefetch.h).
#pragma once

#include "caustica/parallel/prefetch.h"
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// What computeInteraction will read for `hit`, prefetched in two steps a few hits apart: first
/// the triangle's vertex indices, then (once those are in cache) its vertex data.
CA_HD_INLINE void prefetchTriangle(const SceneView& scene, const Hit& hit) {
    if (hit.primId >= scene.numTriangles()) return;  // a miss, or not a triangle
    prefetchRead(&scene.triangles[hit.primId]);
    prefetchRead(&scene.triangleShape[hit.primId]);
}
CA_HD_INLINE void prefetchVertices(const SceneView& scene, const Hit& hit) {
    if (hit.primId >= scene.numTriangles()) return;
    const Vec3u tri = scene.triangles[hit.primId];
    for (uint32_t v : {tri.x, tri.y, tri.z}) {
        prefetchRead(&scene.positions[v]);
        if (!scene.normals.empty()) prefetchRead(&scene.normals[v]);
        if (!scene.uvs.empty()) prefetchRead(&scene.uvs[v]);
    }
}

}  // namespace caustica
