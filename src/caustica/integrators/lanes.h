// lanes.h — independent paths traced side by side by one work item (CA_HD), for the kernels whose
// work item is a whole path: the photon pass, Metropolis proposals and bootstrap samples. Where
// the intersector answers packets of rays (Embree on the host) a work item keeps up to
// laneCount<I>() paths in flight: their next segments go to it as one packet query and their
// shadow rays as another, the hits' triangles are prefetched before the paths take their hits,
// and a lane whose path ends takes the work item's next path. Each path is advanced by its own
// step functions with its own sampler, so its result is the one it has traced alone; only the
// order in which paths finish differs. (The wavefront driver gets full packets from its queues
// instead, wavefront_pass.h.)
//
// traceLanes drives a Policy, which holds the paths of the lanes:
//   bool begin(int lane, size_t item)  puts path `item` in `lane`; false: it traces nothing (the
//                                      policy has finished it)
//   const Ray& ray(int lane)           the segment the lane's path traces next
//   bool hit(int lane, const Hit* hit, const Ray*& shadow)
//                                      the path takes its closest hit (nullptr: a miss); it may
//                                      set `shadow` to a ray to test for occlusion; returns
//                                      whether the path traces another segment
//   void shadow(int lane, bool occluded)  the occlusion of the ray hit() set
//   void end(int lane)                 the lane's path is done
//   void move(int from, int to)        the path of lane `from` now lives in lane `to`
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/accel/intersector.h"
#include "caustica/integrators/hit_prefetch.h"

namespace caustica {

/// Paths a work item keeps in flight: rayPacketSize<I>() (16 with Embree on the host), else 1.
template <class Intersector>
constexpr int laneCount() {
    return rayPacketSize<Intersector>();
}

/// Traces paths 0 .. count - 1 of `policy`, up to laneCount<Intersector>() at a time.
template <class Intersector, class Policy>
CA_HD void traceLanes(const SceneView& scene, const Intersector& accel, size_t count, Policy& policy) {
    constexpr int L = laneCount<Intersector>();
    size_t next = 0;
    const auto fill = [&](int lane) {  // the next path that traces a ray into `lane`
        while (next < count)
            if (policy.begin(lane, next++)) return true;
        return false;
    };
    int used = 0;  // lanes [0, used) hold paths
    while (used < L && fill(used)) ++used;
    Hit hits[L];
    uint32_t found[L];
    bool alive[L];
    while (used > 0) {
        const Ray* rays[L];
        Hit* hitOut[L];
        for (int a = 0; a < used; ++a) {
            rays[a] = &policy.ray(a);
            hitOut[a] = &hits[a];
        }
        intersectPacket(accel, used, rays, hitOut, found);
        if constexpr (L > 1) {
            for (int a = 0; a < used; ++a)
                if (found[a]) prefetchTriangle(scene, hits[a]);
            for (int a = 0; a < used; ++a)
                if (found[a]) prefetchVertices(scene, hits[a]);
        }
        int shadowLanes[L];
        int shadows = 0;
        for (int a = 0; a < used; ++a) {
            const Ray* shadow = nullptr;
            alive[a] = policy.hit(a, found[a] ? &hits[a] : nullptr, shadow);
            if (shadow) {
                shadowLanes[shadows] = a;
                rays[shadows++] = shadow;
            }
        }
        if (shadows > 0) {
            uint32_t occluded[L];
            occludedPacket(accel, shadows, rays, occluded);
            for (int s = 0; s < shadows; ++s) policy.shadow(shadowLanes[s], occluded[s] != 0);
        }
        // Ended paths hand their lanes on; with no path left, the last lane fills the gap.
        for (int a = 0; a < used;) {
            if (alive[a]) {
                ++a;
                continue;
            }
            policy.end(a);
            if (fill(a)) {
                ++a;
                continue;
            }
            if (a < --used) {
                policy.move(used, a);
                alive[a] = alive[used];  // lane a is looked at again
            }
        }
    }
}

}  // namespace caustica
