// intersector.h — the two ray-query objects integrators are templated on. Both offer
//     bool intersect(const Ray&, Hit&) const;  // closest hit with t in (0, ray.tMax)
//     bool occluded(const Ray&) const;         // any hit with t in (0, ray.tMax)
// and, through intersectPacket / occludedPacket below, the same queries for a packet of rays (the
// wavefront's trace stages). EmbreeIntersector answers a packet with Embree's packet queries; every
// other intersector (and every one on a GPU, where a packet is one ray) with the single-ray loop.
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

/// Rays per packet query of intersector I: its `kPacketSize` where it has one (Embree: 16), else 1.
template <class I>
constexpr int rayPacketSize() {
    if constexpr (requires { I::kPacketSize; })
        return I::kPacketSize;
    else
        return 1;
}

/// The packet queries below as a loop of single-ray queries.
template <class I>
CA_HD_INLINE void intersectEach(const I& accel, int n, const Ray* const* rays, Hit* const* hits, uint32_t* found) {
    for (int k = 0; k < n; ++k) {
        Hit hit{};
        found[k] = accel.intersect(*rays[k], hit);
        *hits[k] = hit;
    }
}
template <class I>
CA_HD_INLINE void occludedEach(const I& accel, int n, const Ray* const* rays, uint32_t* occluded) {
    for (int k = 0; k < n; ++k) occluded[k] = accel.occluded(*rays[k]);
}

/// Closest hits of rays[0..n) (n <= rayPacketSize<I>()): found[k] = 1 and hits[k] = the hit, or
/// found[k] = 0 and hits[k] = Hit{} on a miss. The same hits as n single-ray `intersect` calls.
/// `coherent`: the rays start close together in nearly one direction (camera rays of neighbouring
/// samples), which lets a packet intersector traverse them as one (Embree's coherent mode); a
/// hint only, the hits are the same.
template <class I>
CA_HD_INLINE void intersectPacket(const I& accel, int n, const Ray* const* rays, Hit* const* hits,
                                  uint32_t* found, bool coherent = false) {
    if constexpr (rayPacketSize<I>() > 1)
        accel.intersectPacket(n, rays, hits, found, coherent);
    else
        intersectEach(accel, n, rays, hits, found);
}

/// occluded[k] = whether rays[k] is blocked, for k < n (n <= rayPacketSize<I>()).
template <class I>
CA_HD_INLINE void occludedPacket(const I& accel, int n, const Ray* const* rays, uint32_t* occluded) {
    if constexpr (rayPacketSize<I>() > 1)
        accel.occludedPacket(n, rays, occluded);
    else
        occludedEach(accel, n, rays, occluded);
}

}  // namespace caustica
