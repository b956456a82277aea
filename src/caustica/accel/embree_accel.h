// embree_accel.h — the Embree 3 backend (host only). This header does not include Embree's headers
// (the handles are opaque), so any translation unit, nvcc-compiled ones included, may include it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "caustica/accel/embree_isa.h"
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

struct RTCDeviceTy;  // Embree's opaque handle types (RTCDevice, RTCScene)
struct RTCSceneTy;
struct RTCGeometryTy;

namespace caustica {

struct PreparedParallelogram;  // accel/parallelogram_intersect.h

/// Single-ray queries against a committed Embree scene, with the same contract as BvhIntersector:
/// `intersect` fills `hit` (t, primId, b1 = Embree's u, b2 = v) for the closest hit with t in
/// (0, ray.tMax) and returns true, leaving `hit` unchanged on a miss; `occluded` reports any hit in
/// (0, ray.tMax). Host only; a cheap value type, valid while its EmbreeScene lives.
/// The packet queries (reached through intersectPacket / occludedPacket, intersector.h) answer up
/// to kPacketSize rays with rtcIntersect16/8/4 and rtcOccluded16/8/4, `packetWidth` rays per call
/// (chosen by EmbreeScene from the widths Embree runs natively on this CPU; 1: single rays).
struct EmbreeIntersector {
    static constexpr int kPacketSize = 16;

    RTCSceneTy* scene = nullptr;
    uint32_t numTriangles = 0;   // primId = primID for geometry 0, numTriangles + primID for 1,
    uint32_t firstCylinder = 0;  // firstCylinder + primID for 2 (cylinders)
    int packetWidth = 1;         // 16, 8, 4 or 1
    // A scene's few spheres and cylinders (EmbreeSceneOptions::directPrimitives) are not in the
    // Embree scene: each query tests them one by one before asking Embree. Empty otherwise.
    const Sphere* directSpheres = nullptr;
    uint32_t numDirectSpheres = 0;
    const Cylinder* directCylinders = nullptr;
    uint32_t numDirectCylinders = 0;
    // A scene's few parallelogram meshes (EmbreeSceneOptions::directParallelograms), tested as
    // planes before the spheres. Their triangles are not in Embree's scene: the others are, as
    // runs of consecutive scene triangles, run r (geometry 0 for r = 0, else 2 + r) starting at
    // scene triangle triangleRunFirst[r] (null: one run, geometry 0, every triangle).
    const PreparedParallelogram* directQuads = nullptr;
    uint32_t numDirectQuads = 0;
    const uint32_t* triangleRunFirst = nullptr;

    bool hasDirectPrimitives() const { return numDirectSpheres + numDirectCylinders + numDirectQuads > 0; }
    bool intersect(const Ray& ray, Hit& hit) const;
    bool occluded(const Ray& ray) const;
    /// See intersectPacket / occludedPacket (intersector.h); n <= kPacketSize.
    void intersectPacket(int n, const Ray* const* rays, Hit* const* hits, uint32_t* found,
                         bool coherent = false) const;
    void occludedPacket(int n, const Ray* const* rays, uint32_t* occluded) const;
};

/// How EmbreeScene builds its scene (rtcSetSceneFlags).
struct EmbreeSceneOptions {
    /// RTC_SCENE_FLAG_ROBUST: robust traversal and Embree's Pluecker triangle test, watertight
    /// along shared edges; without it, Moeller-Trumbore lets rays through shared edges and
    /// vertices (tests/accel/watertight_test.cpp). Only tests turn it off.
    bool robust = true;
    /// The widest instruction set Embree may use (embree_isa.h: auto leaves it free on CPUs with
    /// AVX-512 whose clock it does not lower and on AMD Zen 3, else caps it at SSE4.2). The cap also bounds the
    /// packet width (16 needs AVX-512, 8 AVX, 4 SSE).
    EmbreeIsa isa = EmbreeIsa::Auto;
    /// Up to this many spheres and cylinders in all are tested by caustica before each Embree
    /// query instead of being Embree user geometry, whose per-ray dispatch (a second BVH, the
    /// callback and its ray-record accessors) costs more than one test: 4-9% fewer instructions
    /// with one sphere, 1-16% more with 2-16 small ones (docs/PERFORMANCE.md, 2026-11-29
    /// evening). More of them go to Embree, whose BVH culls them. Both give the same hits (the
    /// same intersectSphere / intersectCylinder decides). Tests set 0 to force user geometry.
    uint32_t directPrimitives = 1;
    /// Up to this many mesh shapes that are one parallelogram (scene/parallelogram.h: every
    /// rectangle shape) are tested by caustica before each Embree query, as a plane and two edge
    /// coordinates (accel/parallelogram_intersect.h, four rays at a time in packets), and their
    /// triangles left out of Embree's scene. Mitsuba 3 intersects its rectangles analytically too;
    /// in Embree they are two triangles each under RTC_SCENE_FLAG_ROBUST, whose traversal and
    /// Pluecker test cost 1.2-1.8x a non-robust one per ray (docs/PERFORMANCE.md). Same surfaces,
    /// other last bits of t and the barycentrics. More of them, or 0: all stay in Embree.
    uint32_t directParallelograms = 16;
};

/// Whether Embree may read `positions` in place (rtcSetSharedGeometryBuffer): its 16-byte vertex
/// loads read 4 bytes past the last vertex, which must lie inside the allocation, so the vector
/// needs spare capacity (reserveVertexPadding, scene.h, gives it one vertex).
bool sharesVertexArray(const std::vector<Vec3f>& positions);

/// An Embree device and scene built from a Scene: triangles as geometry 0 (RTC_GEOMETRY_TYPE_
/// TRIANGLE over the Scene's own index and vertex arrays, shared, not copied; the vertices are
/// copied into a padded Embree buffer only where sharesVertexArray is false), spheres and
/// cylinders as user geometries 1 and 2 whose callbacks run caustica's own intersectSphere/
/// intersectCylinder, or, when there are at most `options.directPrimitives` of them, tested by
/// the intersector itself before each Embree query; likewise up to `options.directParallelograms`
/// parallelogram meshes, whose triangles then stay out of Embree's scene (the others go in as
/// runs of consecutive triangles, each a triangle geometry over the same shared arrays). Built with RTC_SCENE_FLAG_ROBUST unless
/// `options.robust` is false. Embree reads `scene.triangles`, `scene.positions` (while building),
/// the callbacks and the direct tests `scene.spheres` and `scene.cylinders`, so `scene` must
/// outlive this object and its arrays must not be resized
/// or reassigned meanwhile (moving the Scene keeps them). Errors reported by Embree are thrown as
/// caustica::Error.
class EmbreeScene {
public:
    explicit EmbreeScene(const Scene& scene, const EmbreeSceneOptions& options = {});
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    EmbreeIntersector intersector() const;
    /// How many parallelogram shapes the intersector tests itself (options.directParallelograms).
    uint32_t directParallelogramCount() const;
    /// Rays per Embree packet call: the widest packet Embree runs natively on this CPU (16, 8 or
    /// 4), else 1 (single rays). Narrower ones work too (set EmbreeIntersector::packetWidth).
    int packetWidth() const { return packetWidth_; }
    /// The widest packet (16, 8, 4 or 1) Embree runs natively on this CPU under the cap.
    int nativePacketWidth() const { return nativePacketWidth_; }
    /// The instruction-set cap Embree was created with (options.isa resolved, never Auto).
    EmbreeIsa isa() const { return isa_; }
    double buildMilliseconds() const { return buildMilliseconds_; }
    /// Whether Embree reads the Scene's positions in place (else its own padded copy).
    bool sharesVertices() const { return sharesVertices_; }

private:
    void check(const char* what);  // throws caustica::Error if the device reports an error
    void release();
    void addTriangleRun(const Scene& scene, uint32_t first, uint32_t count, unsigned geomId);
    void takeDirectParallelograms(const Scene& scene, uint32_t limit);
    template <class Prim>
    void addUserGeometry(const std::vector<Prim>& prims, unsigned geomId, const char* what);

    RTCDeviceTy* device_ = nullptr;
    RTCSceneTy* scene_ = nullptr;
    uint32_t numTriangles_ = 0;
    uint32_t firstCylinder_ = 0;
    int packetWidth_ = 1;
    int nativePacketWidth_ = 1;
    const Sphere* directSpheres_ = nullptr;  // see EmbreeIntersector
    uint32_t numDirectSpheres_ = 0;
    const Cylinder* directCylinders_ = nullptr;
    uint32_t numDirectCylinders_ = 0;
    std::vector<PreparedParallelogram> directQuads_;  // see EmbreeIntersector
    std::vector<uint32_t> runFirst_, runCount_;  // Embree's runs of triangles (see EmbreeIntersector)
    EmbreeIsa isa_ = EmbreeIsa::Widest;
    bool sharesVertices_ = false;
    double buildMilliseconds_ = 0;
    std::string lastMessage_;  // filled by the device's error callback
};

}  // namespace caustica
