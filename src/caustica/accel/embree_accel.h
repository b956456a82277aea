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

    bool hasDirectPrimitives() const { return numDirectSpheres + numDirectCylinders > 0; }
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
/// the intersector itself before each Embree query. Built with RTC_SCENE_FLAG_ROBUST unless
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

    EmbreeIntersector intersector() const {
        return EmbreeIntersector{scene_,         numTriangles_,     firstCylinder_,   packetWidth_,
                                 directSpheres_, numDirectSpheres_, directCylinders_, numDirectCylinders_};
    }
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
    void setTriangleBuffers(RTCGeometryTy* geom, const Scene& scene);
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
    EmbreeIsa isa_ = EmbreeIsa::Widest;
    bool sharesVertices_ = false;
    double buildMilliseconds_ = 0;
    std::string lastMessage_;  // filled by the device's error callback
};

}  // namespace caustica
