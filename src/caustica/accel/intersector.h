// intersector.h — the two ray-query objects integrators are templated on. Both offer
//     bool intersect(const Ray&, Hit&) const;  // closest hit with t in (0, ray.tMax)
//     bool occluded(const Ray&) const;         // any hit with t in (0, ray.tMax)
// BvhIntersector is shared kernel code (CPU and GPU); EmbreeIntersector (embree_accel.h) is host
// only. embree_accel.h includes no Embree header, so this header compiles under nvcc.
#pragma once

#include "caustica/accel/bvh.h"
#include "caustica/accel/bvh_traversal.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// Ray queries through the own BVH with a chosen traversal (BvhTraversal; ShortStackSize is the
/// ring-buffer size of BvhTraversal::ShortStack, a power of two). A plain value (two structs of
/// spans) that kernels take by value; on the GPU both views must point to device copies,
/// including bvh.parents for the ShortStack and Stackless variants (left empty, those find
/// parents by descending from the root, which is correct but slow).
template <BvhTraversal Traversal, int ShortStackSize = kBvhShortStackSize>
struct BvhIntersectorT {
    BvhView bvh;
    SceneView scene;

    /// Closest hit in (0, ray.tMax): fills `hit` and returns true; `hit` is unchanged on a miss.
    CA_HD bool intersect(const Ray& ray, Hit& hit) const {
        return bvhIntersect<Traversal, ShortStackSize>(bvh, scene, ray, hit);
    }
    /// True if any primitive is hit in (0, ray.tMax).
    CA_HD bool occluded(const Ray& ray) const {
        return bvhOccluded<Traversal, ShortStackSize>(bvh, scene, ray);
    }
};

/// The default: full-stack traversal.
using BvhIntersector = BvhIntersectorT<BvhTraversal::Stack>;

}  // namespace caustica
