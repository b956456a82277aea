// path_lanes.h — pathRadiance for a few independent paths side by side (CA_HD), for the kernels
// whose work item is one whole path (Metropolis proposals and bootstrap samples): where the
// intersector answers packets of rays (Embree on the host), the live paths' closest-hit rays go
// to it as one packet query and their shadow rays as another, and the hits' triangles are
// prefetched before the paths are shaded. Each path takes the step functions of pathRadiance
// (path_kernel.h) in the same order with its own sampler, so its radiance and ray count are bit
// for bit those of pathRadiance (tests/integrators/path_lanes_test.cpp). With packets of one ray
// (the own BVH, a GPU) it is pathRadiance for each path.
#pragma once

#include <cstdint>

#include "caustica/accel/intersector.h"
#include "caustica/integrators/hit_prefetch.h"
#include "caustica/integrators/path/path_kernel.h"

namespace caustica {

/// Paths one work item traces side by side: rayPacketSize<I>() (one packet), or 1.
template <class Intersector>
constexpr int pathLaneCount() {
    return rayPacketSize<Intersector>();
}

/// radiance[j] = pathRadiance(scene, accel, samplers[j], cameraRays[j], settings, rays[j]) for
/// j < n <= pathLaneCount<Intersector>() (rays[j] counts path j's rays; it is set, not added to).
template <class Intersector, class Sampler>
CA_HD void pathRadianceLanes(const SceneView& scene, const Intersector& accel, Sampler* samplers,
                             const Ray* cameraRays, int n, const PathSettings& settings, Spectrum* radiance,
                             uint32_t* rays) {
    constexpr int L = pathLaneCount<Intersector>();
    if constexpr (L == 1) {
        for (int j = 0; j < n; ++j) {
            rays[j] = 0;
            radiance[j] = pathRadiance(scene, accel, samplers[j], cameraRays[j], settings, rays[j]);
        }
    } else {
        PathState paths[L];
        ShadowRay shadows[L];
        Hit hits[L];
        int live[L];  // lanes whose path traces its ray next, in lane order
        int liveCount = 0;
        for (int j = 0; j < n; ++j) {
            rays[j] = 0;
            if (startPath(paths[j], cameraRays[j], settings)) live[liveCount++] = j;
        }
        while (liveCount > 0) {
            const Ray* packet[L];
            Hit* hitOut[L];
            uint32_t found[L];
            for (int a = 0; a < liveCount; ++a) {
                packet[a] = &paths[live[a]].ray;
                hitOut[a] = &hits[live[a]];
            }
            intersectPacket(accel, liveCount, packet, hitOut, found);
            for (int a = 0; a < liveCount; ++a)
                if (found[a]) prefetchTriangle(scene, hits[live[a]]);
            for (int a = 0; a < liveCount; ++a)
                if (found[a]) prefetchVertices(scene, hits[live[a]]);
            int shadowLanes[L];
            int shadowCount = 0, stillLive = 0;
            for (int a = 0; a < liveCount; ++a) {
                const int j = live[a];
                ++rays[j];
                if (!found[a]) {
                    missPath(scene, paths[j], settings);
                    continue;
                }
                bool hasShadow = false;
                const bool alive = shadeHit(scene, paths[j], hits[j], samplers[j], settings, shadows[j], hasShadow);
                if (hasShadow) {
                    shadowLanes[shadowCount] = j;
                    packet[shadowCount++] = &shadows[j].ray;
                }
                if (alive) live[stillLive++] = j;  // stillLive <= a: live[a] was read already
            }
            if (shadowCount > 0) {
                uint32_t occluded[L];
                occludedPacket(accel, shadowCount, packet, occluded);
                for (int s = 0; s < shadowCount; ++s) {
                    const int j = shadowLanes[s];
                    ++rays[j];
                    addShadowContribution(paths[j], shadows[j], occluded[s] != 0);
                }
            }
            liveCount = stillLive;
        }
        for (int j = 0; j < n; ++j) radiance[j] = paths[j].radiance;
    }
}

}  // namespace caustica
