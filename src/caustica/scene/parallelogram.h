// parallelogram.h — mesh shapes that are one parallelogram (every rectangle shape): two triangles
// sharing a diagonal whose other corners are symmetric about its middle. Light setup samples such
// an emitter as a parallelogram (Light::isQuad); Embree's intersector and the own BVH test such
// shapes as one plane and two edge coordinates, not as two triangles (accel/parallelogram_intersect.h).
#pragma once

#include <cstdint>

#include "caustica/scene/scene.h"

namespace caustica {

/// A two-triangle mesh shape as the points corner + u·edgeU + v·edgeV, u, v in [0, 1]. Triangle
/// `first` is the half u + v <= 1 (its vertices corner, corner + edgeU, corner + edgeV), triangle
/// `second` the half u + v >= 1. `slots[h][j]` is which vertex (0, 1, 2) of half h's triangle
/// sits at: h = 0: j = 0 corner, 1 corner + edgeU, 2 corner + edgeV; h = 1: j = 0 the far corner
/// corner + edgeU + edgeV, 1 corner + edgeU, 2 corner + edgeV.
struct MeshParallelogram {
    Vec3f corner, edgeU, edgeV;
    uint32_t first = 0, second = 0;
    uint8_t slots[2][3] = {{0, 1, 2}, {0, 1, 2}};
};

/// Whether mesh shape `shape` is one parallelogram: two triangles sharing two vertex positions
/// (the diagonal), their other corners symmetric about the diagonal's middle within 1e-6 of the
/// shape's size. Fills `out` when it is. Orientation and normals are not looked at.
bool meshParallelogram(const Scene& scene, const Shape& shape, MeshParallelogram& out);

}  // namespace caustica
