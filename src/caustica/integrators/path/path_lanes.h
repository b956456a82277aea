// path_lanes.h — the path tracer's paths side by side (lanes.h) for the kernels whose work item
// is one whole path (Metropolis proposals and bootstrap samples): each path takes the step
// functions of pathRadiance (path_kernel.h) in the same order with its own sampler, so its
// radiance and ray count are bit for bit pathRadiance's (tests/integrators/path_lanes_test.cpp).
// With packets of one ray (the own BVH, a GPU) it is pathRadiance for each path.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/integrators/lanes.h"
#include "caustica/integrators/path/path_kernel.h"

namespace caustica {

/// traceLanes' policy for path tracing (see tracePathsSideBySide).
template <int L, class Sampler, class Start, class Finish>
struct PathLanes {
    const SceneView& scene;
    const PathSettings& settings;
    Start& start;
    Finish& finish;
    PathState paths[L];
    ShadowRay shadows[L];
    Sampler samplers[L];
    size_t items[L];
    uint32_t rays[L];

    CA_HD bool begin(int lane, size_t item) {
        items[lane] = item;
        rays[lane] = 0;
        const Ray cameraRay = start(item, samplers[lane]);
        if (startPath(paths[lane], cameraRay, settings)) return true;
        finish(item, samplers[lane], paths[lane].radiance, 0u);
        return false;
    }
    CA_HD const Ray& ray(int lane) const { return paths[lane].ray; }
    CA_HD bool hit(int lane, const Hit* hit, const Ray*& shadow) {
        ++rays[lane];
        if (!hit) {
            missPath(scene, paths[lane], settings);
            return false;
        }
        bool hasShadow = false;
        const bool alive = shadeHit(scene, paths[lane], *hit, samplers[lane], settings, shadows[lane], hasShadow);
        if (hasShadow) shadow = &shadows[lane].ray;
        return alive;
    }
    CA_HD void shadow(int lane, bool occluded) {
        ++rays[lane];
        addShadowContribution(paths[lane], shadows[lane], occluded);
    }
    CA_HD void end(int lane) { finish(items[lane], samplers[lane], paths[lane].radiance, rays[lane]); }
    CA_HD void move(int from, int to) {
        paths[to] = paths[from];
        shadows[to] = shadows[from];
        samplers[to] = samplers[from];
        items[to] = items[from];
        rays[to] = rays[from];
    }
};

/// Traces paths 0 .. count - 1 side by side: start(item, sampler) sets up path item's sampler
/// (assigned to a default-constructed Sampler) and returns its camera ray; finish(item, sampler,
/// radiance, rays) receives what pathRadiance would return for it and the rays it traced.
template <class Intersector, class Sampler, class Start, class Finish>
CA_HD void tracePathsSideBySide(const SceneView& scene, const Intersector& accel, const PathSettings& settings,
                                size_t count, Start&& start, Finish&& finish) {
    constexpr int L = laneCount<Intersector>();
    if constexpr (L == 1) {
        for (size_t item = 0; item < count; ++item) {
            Sampler sampler;
            const Ray cameraRay = start(item, sampler);
            uint32_t rays = 0;
            const Spectrum radiance = pathRadiance(scene, accel, sampler, cameraRay, settings, rays);
            finish(item, sampler, radiance, rays);
        }
    } else {
        PathLanes<L, Sampler, Start, Finish> lanes{scene, settings, start, finish, {}, {}, {}, {}, {}};
        traceLanes(scene, accel, count, lanes);
    }
}

}  // namespace caustica
