// first_hit_intersector.h — an intersector that answers the closest-hit query of one given ray from
// a hit found before. A megakernel that also writes AOVs (megakernel_pass.h, aov_kernel.h) traces
// each camera ray once: the AOVs take its hit, and the radiance estimator's query for that same
// ray gets the stored hit instead of tracing it again. Any other query (another ray, occlusion)
// goes to the wrapped intersector, so the estimate is the one the wrapped intersector gives.
#pragma once

#include "caustica/scene/ray.h"

namespace caustica {

template <class Intersector>
struct FirstHitIntersector {
    const Intersector& accel;
    Ray ray;              // the query answered from `hit`
    Hit hit;              // its closest hit (unchanged from Hit{} on a miss)
    bool found = false;   // whether `hit` is one
    bool stored = false;  // whether trace() ran

    CA_HD explicit FirstHitIntersector(const Intersector& wrapped) : accel(wrapped) {}

    /// Traces `r` once through the wrapped intersector and keeps the answer.
    CA_HD void trace(const Ray& r) {
        ray = r;
        found = accel.intersect(r, hit);
        stored = true;
    }
    /// The stored answer for the stored ray (bit-equal origin, direction and tMax), else a query.
    CA_HD bool intersect(const Ray& r, Hit& h) const {
        if (stored && r.o.x == ray.o.x && r.o.y == ray.o.y && r.o.z == ray.o.z && r.d.x == ray.d.x &&
            r.d.y == ray.d.y && r.d.z == ray.d.z && r.tMax == ray.tMax) {
            if (found) h = hit;
            return found;
        }
        return accel.intersect(r, h);
    }
    CA_HD bool occluded(const Ray& r) const { return accel.occluded(r); }
};

}  // namespace caustica
