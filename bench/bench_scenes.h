// bench_scenes.h — the scenes and ray sets shared by the ray benchmarks (bench_rays on the CPU,
// bench_gpu_rays on the GPU), so that both measure exactly the same rays:
//   makeProceduralScene  a displaced icosphere (20 * 4^levels triangles; 7 levels = 327,680) on a
//                        ground quad, 640 x 480 camera
//   makeRaySets          camera rays (pixel centres), diffuse bounces and shadow rays from their
//                        first hits (closest hit found with the own BVH)
// Host code only (header-only so that a .cu benchmark can include it).
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "caustica/accel/bvh.h"
#include "caustica/accel/intersector.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/scene.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"

namespace caustica::bench {

// ---- procedural scene: displaced icosphere --------------------------------------------------

/// Smooth 3D value noise in [-1, 1] from hashed lattice values (trilinear, smoothstep-faded).
inline Float valueNoise(Vec3f p) {
    const Float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    auto lattice = [](int x, int y, int z) {
        const uint64_t h =
            hashCombine(hashCombine(mix64(uint64_t(uint32_t(x))), uint32_t(y)), uint32_t(z));
        return 2 * uniformFloat(h) - 1;
    };
    auto fade = [](Float t) { return t * t * (3 - 2 * t); };
    const Float ux = fade(p.x - fx), uy = fade(p.y - fy), uz = fade(p.z - fz);
    const int x = int(fx), y = int(fy), z = int(fz);
    Float c[2][2];
    for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
            c[j][k] = lerp(ux, lattice(x, y + j, z + k), lattice(x + 1, y + j, z + k));
    return lerp(uz, lerp(uy, c[0][0], c[1][0]), lerp(uy, c[0][1], c[1][1]));
}

inline Float fbm(Vec3f p) {
    Float sum = 0, amp = 0.5f;
    for (int octave = 0; octave < 5; ++octave, p = p * 2.03f, amp *= 0.5f)
        sum += amp * valueNoise(p);
    return sum;
}

/// An icosahedron subdivided `levels` times (20 * 4^levels triangles), projected to the unit
/// sphere and displaced radially by fractal noise, standing on a large ground quad.
inline Scene makeProceduralScene(int levels) {
    Scene scene;
    const Float g = (1 + std::sqrt(5.0f)) / 2;
    std::vector<Vec3f> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                            {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                            {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<Vec3u> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (Vec3f& p : v) p = normalize(p);
    for (int level = 0; level < levels; ++level) {
        std::unordered_map<uint64_t, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const uint64_t key = (uint64_t(min(a, b)) << 32) | max(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            v.push_back(normalize(v[a] + v[b]));
            return midpoints[key] = uint32_t(v.size() - 1);
        };
        std::vector<Vec3u> next;
        next.reserve(f.size() * 4);
        for (const Vec3u& t : f) {
            const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z),
                           ca = midpoint(t.z, t.x);
            next.push_back({t.x, ab, ca});
            next.push_back({t.y, bc, ab});
            next.push_back({t.z, ca, bc});
            next.push_back({ab, bc, ca});
        }
        f.swap(next);
    }
    for (Vec3f& p : v) p = p * (1 + 0.35f * fbm(p * 3.0f + Vec3f(7.1f, 3.3f, 1.7f)));

    Shape mesh;
    mesh.primCount = uint32_t(f.size()) + 2;
    scene.shapes.push_back(mesh);
    scene.positions = v;
    scene.triangles = f;
    const uint32_t base = uint32_t(scene.positions.size());
    for (Vec3f p : {Vec3f(-20, -1.25f, -20), Vec3f(20, -1.25f, -20), Vec3f(20, -1.25f, 20),
                    Vec3f(-20, -1.25f, 20)})
        scene.positions.push_back(p);
    scene.triangles.push_back({base, base + 2, base + 1});
    scene.triangles.push_back({base, base + 3, base + 2});
    scene.triangleShape.assign(scene.triangles.size(), 0);
    reserveVertexPadding(scene);

    Camera& cam = scene.camera;
    cam.width = 640;
    cam.height = 480;
    cam.tanHalfY = std::tan(radians(20.0f));
    cam.tanHalfX = cam.tanHalfY * Float(cam.width) / Float(cam.height);
    cam.worldFromCamera = lookAt(Vec3f(0.6f, 0.9f, 3.4f), Vec3f(0, -0.15f, 0), Vec3f(0, 1, 0));
    return scene;
}

// ---- ray sets --------------------------------------------------------------------------------

/// Where shadow rays go: the centre of the scene's emitting triangles if it has any (the
/// Cornell box's ceiling light), else a point high above the scene.
inline Vec3f shadowTarget(const Scene& scene) {
    Bounds3f emitters;
    for (size_t i = 0; i < scene.triangles.size(); ++i)
        if (scene.shapes[scene.triangleShape[i]].light >= 0)
            emitters.extend(scene.primitiveBounds(uint32_t(i)));
    if (!emitters.empty()) return emitters.center();
    const Bounds3f b = scene.bounds();
    return Vec3f(b.center().x, b.hi.y + b.diagonal().y, b.center().z);
}

/// The three ray sets of a scene (see the file comment); bounce and shadow rays exist only for
/// pixels whose camera ray hits something.
struct RaySets {
    std::vector<Ray> camera, bounce, shadow;
};

/// Camera rays, then diffuse bounces and shadow rays from their first hits (found with the BVH).
inline RaySets makeRaySets(const Scene& scene, const Bvh& bvh) {
    RaySets sets;
    const Camera& cam = scene.camera;
    const SceneView view = scene.view();
    const BvhIntersector it{bvh.view(), view};
    const Vec3f light = shadowTarget(scene);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const Ray ray = generateCameraRay(cam, Vec2f(x + 0.5f, y + 0.5f));
            sets.camera.push_back(ray);
            Hit hit;
            if (!it.intersect(ray, hit)) continue;
            const SurfaceInteraction si = computeInteraction(view, ray, hit);
            const Vec3f n = faceForward(si.ng, -ray.d);
            IndependentSampler sampler(uint64_t(y) * cam.width + x, 0, 7);
            const Vec3f dir = Frame(n).toWorld(sampleCosineHemisphere(sampler.get2D()));
            sets.bounce.push_back(spawnRay(si.p, n, dir));
            sets.shadow.push_back(spawnRayTo(si.p, n, light, Vec3f(0, 0, 0)));
        }
    return sets;
}

}  // namespace caustica::bench
