// test_scenes.h — random scenes, random rays and the brute-force reference for the accel tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "caustica/accel/primitive_intersect.h"
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"
#include "caustica/util/rng.h"
#include "scene/scene_builder.h"

namespace caustica::test {

/// Deterministic uniform numbers from the project's counter-based sampler.
/// A float's bits, for comparisons to the bit.
inline uint32_t bitsOf(Float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

class TestRng {
public:
    explicit TestRng(uint64_t seed) : sampler_(seed, 0, 0x5eed) {}
    Float uniform() { return sampler_.get1D(); }
    Float uniform(Float lo, Float hi) { return lo + (hi - lo) * uniform(); }
    uint32_t index(uint32_t n) { return min(uint32_t(uniform() * Float(n)), n - 1); }
    Vec3f inBox(Vec3f lo, Vec3f hi) {
        const Float x = uniform(lo.x, hi.x), y = uniform(lo.y, hi.y);
        return Vec3f(x, y, uniform(lo.z, hi.z));
    }
    /// Uniform direction on the unit sphere.
    Vec3f direction() {
        const Float z = 1 - 2 * uniform(), phi = 2 * kPi * uniform();
        const Float r = safeSqrt(1 - z * z);
        return Vec3f(r * std::cos(phi), r * std::sin(phi), z);
    }

private:
    IndependentSampler sampler_;
};

/// Settings of makeRandomScene: a triangle soup (one mesh shape) plus spheres (one shape each).
struct RandomSceneOptions {
    uint32_t numTriangles = 100;
    uint32_t numSpheres = 0;
    Vec3f center{0, 0, 0};  // the soup fills center +- extent / 2
    Float extent = 10;
    Float primitiveSize = 1;       // triangle vertex spread and largest sphere radius
    Float degenerateFraction = 0;  // share of zero-area / collinear triangles
    uint64_t seed = 1;
};

/// Options of `tris` triangles and `spheres` spheres drawn from `seed`, the rest default.
inline RandomSceneOptions sceneOf(uint32_t tris, uint32_t spheres, uint64_t seed) {
    RandomSceneOptions o;
    o.numTriangles = tris;
    o.numSpheres = spheres;
    o.seed = seed;
    return o;
}

/// Appends one mesh shape (empty triangle list allowed) whose triangles are added later.
inline uint32_t addMeshShape(Scene& scene, uint32_t primOffset, uint32_t primCount) {
    Shape shape;
    shape.type = ShapeType::Mesh;
    shape.primOffset = primOffset;
    shape.primCount = primCount;
    scene.shapes.push_back(shape);
    return uint32_t(scene.shapes.size() - 1);
}

inline void addTriangle(Scene& scene, uint32_t shape, Vec3f a, Vec3f b, Vec3f c) {
    const uint32_t base = uint32_t(scene.positions.size());
    scene.positions.push_back(a);
    scene.positions.push_back(b);
    scene.positions.push_back(c);
    scene.triangles.push_back(Vec3u{base, base + 1, base + 2});
    scene.triangleShape.push_back(shape);
}

inline Scene makeRandomScene(const RandomSceneOptions& opt) {
    Scene scene;
    TestRng rng(opt.seed);
    const Vec3f lo = opt.center - Vec3f(opt.extent / 2), hi = opt.center + Vec3f(opt.extent / 2);
    const uint32_t mesh = addMeshShape(scene, 0, opt.numTriangles);
    const Float s = opt.primitiveSize;
    for (uint32_t i = 0; i < opt.numTriangles; ++i) {
        const Vec3f c = rng.inBox(lo, hi);
        Vec3f a = c + rng.inBox(Vec3f(-s), Vec3f(s));
        Vec3f b = c + rng.inBox(Vec3f(-s), Vec3f(s));
        Vec3f d = c + rng.inBox(Vec3f(-s), Vec3f(s));
        if (rng.uniform() < opt.degenerateFraction) {
            switch (rng.index(4)) {
            case 0: b = a; break;                   // repeated vertex
            case 1: b = d = a; break;               // a point
            case 2: d = a + (b - a) * 0.5f; break;  // (nearly) collinear
            default: d = b; break;                  // repeated vertex
            }
        }
        addTriangle(scene, mesh, a, b, d);
    }
    for (uint32_t i = 0; i < opt.numSpheres; ++i)
        addSphere(scene, rng.inBox(lo, hi), s * rng.uniform(0.05f, 1.0f));
    return scene;
}

/// A mesh shape of two triangles forming the parallelogram corner + [0,1]·edgeU + [0,1]·edgeV
/// (as a rectangle shape is), split along the diagonal from corner + edgeU to corner + edgeV;
/// `rotate` (0-2) turns both triangles' vertex order, so every vertex slot gets every corner.
inline uint32_t addParallelogram(Scene& scene, Vec3f corner, Vec3f edgeU, Vec3f edgeV, int rotate = 0) {
    const uint32_t shape = addMeshShape(scene, uint32_t(scene.triangles.size()), 2);
    Vec3f a[3] = {corner, corner + edgeU, corner + edgeV};
    Vec3f b[3] = {corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
    for (int r = 0; r < rotate; ++r) {
        std::swap(a[0], a[1]), std::swap(a[1], a[2]);
        std::swap(b[0], b[1]), std::swap(b[1], b[2]);
    }
    addTriangle(scene, shape, a[0], a[1], a[2]);
    addTriangle(scene, shape, b[0], b[1], b[2]);
    return shape;
}

/// A height-field mesh of n x n quads over center + [-halfSize, halfSize]^2 in x and z, with
/// smooth bumps of the given amplitude in y: a large, closed-surface-free mesh for offset tests.
inline Scene makeTerrain(uint32_t n, Float halfSize, Vec3f center, Float amplitude) {
    Scene scene;
    const uint32_t mesh = addMeshShape(scene, 0, 2 * n * n);
    for (uint32_t j = 0; j <= n; ++j)
        for (uint32_t i = 0; i <= n; ++i) {
            const Float u = Float(i) / Float(n), v = Float(j) / Float(n);
            const Float h = amplitude * std::sin(11 * u + 2) * std::cos(7 * v - 1) *
                            std::sin(23 * u * v + 0.5f);
            scene.positions.push_back(center +
                                      Vec3f((2 * u - 1) * halfSize, h, (2 * v - 1) * halfSize));
        }
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            scene.triangles.push_back(Vec3u{a, b, d});
            scene.triangles.push_back(Vec3u{a, d, c});
            scene.triangleShape.push_back(mesh);
            scene.triangleShape.push_back(mesh);
        }
    return scene;
}

/// A point on primitive `id` (uniform barycentrics for triangles, surface point for spheres).
inline Vec3f pointOnPrimitive(const Scene& scene, uint32_t id, TestRng& rng) {
    if (id < scene.triangles.size()) {
        Float u = rng.uniform(), v = rng.uniform();
        if (u + v > 1) {
            u = 1 - u;
            v = 1 - v;
        }
        const Vec3u t = scene.triangles[id];
        const Vec3f p0 = scene.positions[t.x];
        return p0 + (scene.positions[t.y] - p0) * u + (scene.positions[t.z] - p0) * v;
    }
    if (id >= scene.triangles.size() + scene.spheres.size()) {  // a cylinder: a point of its axis
        const Cylinder& c = scene.cylinders[id - scene.triangles.size() - scene.spheres.size()];
        return c.base + c.axis * (c.length * rng.uniform());
    }
    const Sphere& s = scene.spheres[id - scene.triangles.size()];
    return s.center + rng.direction() * s.radius;
}

/// Rays of several kinds: random origin and direction (non-unit lengths), rays aimed at points on
/// primitives (many hits, some stopping short like shadow rays), and rays with small tMax.
inline std::vector<Ray> makeRandomRays(const Scene& scene, uint32_t count, uint64_t seed) {
    std::vector<Ray> rays;
    TestRng rng(seed);
    Bounds3f b = scene.bounds();
    if (b.empty()) b = Bounds3f{Vec3f(-1), Vec3f(1)};
    const Vec3f margin = b.diagonal() * 0.25f;
    const Vec3f lo = b.lo - margin, hi = b.hi + margin;
    const uint32_t numPrims = scene.numPrimitives();
    for (uint32_t i = 0; i < count; ++i) {
        Ray r;
        r.o = rng.inBox(lo, hi);
        const uint32_t kind = rng.index(4);
        if (kind == 0 || numPrims == 0) {
            r.d = rng.direction() * rng.uniform(0.1f, 10.0f);
        } else {
            const Vec3f target = pointOnPrimitive(scene, rng.index(numPrims), rng);
            r.d = target - r.o;
            if (kind == 2) r.tMax = 1 - 1e-4f;                // shadow ray towards target
            if (kind == 3) r.tMax = rng.uniform(0.0f, 1.5f);  // arbitrary cut-off
        }
        rays.push_back(r);
    }
    return rays;
}

/// The reference: every primitive tested, closest kept.
inline bool bruteForceIntersect(const SceneView& scene, const Ray& ray, Hit& hit) {
    Hit best;
    for (uint32_t id = 0; id < scene.numPrimitives(); ++id)
        intersectPrimitive(scene, id, ray, best);
    if (!best.valid()) return false;
    hit = best;
    return true;
}

inline bool bruteForceOccluded(const SceneView& scene, const Ray& ray) {
    for (uint32_t id = 0; id < scene.numPrimitives(); ++id) {
        Hit h;
        if (intersectPrimitive(scene, id, ray, h)) return true;
    }
    return false;
}

/// t of `ray` against primitive `id` alone, or -1 on a miss.
inline Float primitiveT(const SceneView& scene, uint32_t id, const Ray& ray) {
    Hit h;
    return intersectPrimitive(scene, id, ray, h) ? h.t : Float(-1);
}

}  // namespace caustica::test
