// emitter_boxes.h — padded bounding boxes of the emitting shapes: a cheap, conservative test of
// "can this ray's first hit be an emitter?" (kernel code, CA_HD), so that a caller which traces a
// ray only to add the emission it finds (sppm's visible point: the BSDF sample's emission,
// MIS-weighted against NEE) skips the full closest-hit trace when no emitter lies along the ray.
//
// Conservative, never exact: `mayHitEmitter` is true for every ray whose closest hit (any
// intersector) is on an emitting shape, and false only when the ray passes no emitter's box, so a
// caller that traces the ray in full whenever it is true finds exactly what it found before. The
// boxes are padded by a few hundred float epsilons of the scene's size to cover both the slab
// test's rounding and the intersector's. Not usable (callers trace every ray) when a ray that
// hits nothing can find emission (an environment emitter) or when there are more emitting shapes
// than kMaxBoxes (a large emitter set gains little from a box each).
#pragma once

#include <cstdint>

#include "caustica/scene/ray.h"
#include "caustica/util/math.h"

namespace caustica {

struct Scene;

struct EmitterBoxes {
    static constexpr uint32_t kMaxBoxes = 8;
    bool usable = false;  // false: every ray may find emission (callers trace it)
    uint32_t count = 0;   // boxes in use (0 and usable: no ray can find emission)
    Bounds3f boxes[kMaxBoxes];

    /// True when `ray` may hit an emitter in (0, ray.tMax): it passes through an emitter's box,
    /// or the boxes are not usable.
    CA_HD bool mayHitEmitter(const Ray& ray) const {
        if (!usable) return true;
        for (uint32_t k = 0; k < count; ++k)
            if (rayMeetsBox(ray, boxes[k])) return true;
        return false;
    }

    /// Slab test (Kay and Kajiya 1986) of the segment (0, tMax] (t slightly beyond tMax and
    /// below 0 accepted: the box is padded, so exactness at the ends does not matter). An axis
    /// the ray is parallel to is tested by the origin's coordinate alone (no 0 · inf).
    CA_HD static bool rayMeetsBox(const Ray& ray, const Bounds3f& b) {
        Float tNear = -kInfinity, tFar = ray.tMax;
        for (int axis = 0; axis < 3; ++axis) {
            const Float o = axis == 0 ? ray.o.x : (axis == 1 ? ray.o.y : ray.o.z);
            const Float d = axis == 0 ? ray.d.x : (axis == 1 ? ray.d.y : ray.d.z);
            const Float lo = axis == 0 ? b.lo.x : (axis == 1 ? b.lo.y : b.lo.z);
            const Float hi = axis == 0 ? b.hi.x : (axis == 1 ? b.hi.y : b.hi.z);
            if (d == 0) {
                if (o < lo || o > hi) return false;
                continue;
            }
            const Float inv = 1 / d;
            Float t0 = (lo - o) * inv, t1 = (hi - o) * inv;
            if (t0 > t1) {
                const Float t = t0;
                t0 = t1;
                t1 = t;
            }
            tNear = max(tNear, t0);
            tFar = min(tFar, t1);
        }
        return tNear <= tFar && tFar >= 0;
    }
};

/// The boxes of `scene`'s emitting shapes (host, O(primitives)): one box per shape with a light,
/// padded by 1e-4 of its own diagonal plus 1e-5 of the scene's size (largest |coordinate| plus
/// diagonal of its bounds); not usable with an environment emitter, more than kMaxBoxes emitting
/// shapes, or a box that is not finite.
EmitterBoxes buildEmitterBoxes(const Scene& scene);

}  // namespace caustica
