// embree_accel.cpp — Embree 3 scene construction, single-ray and packet queries (see embree_accel.h).
#include "caustica/accel/embree_accel.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include <embree3/rtcore.h>

#include "caustica/accel/intersector.h"
#include "caustica/accel/parallelogram_intersect.h"
#include "caustica/accel/primitive_intersect.h"
#include "caustica/accel/sphere_lanes.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

constexpr unsigned kTriangleGeomId = 0;  // the first run of triangles
constexpr unsigned kSphereGeomId = 1;
constexpr unsigned kSecondTriangleRunGeomId = 3;  // the other runs (EmbreeIntersector::triangleRunFirst)

const char* errorName(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error code";
}

void errorCallback(void* user, RTCError code, const char* message) {
    *static_cast<std::string*>(user) =
        std::string(errorName(code)) + (message ? ": " : "") + (message ? message : "");
}

// ---- sphere and cylinder user geometry: the callbacks run caustica's own intersection tests ----

constexpr unsigned kCylinderGeomId = 2;

Bounds3f primBounds(const Sphere& s) {
    return Bounds3f{s.center - Vec3f(s.radius), s.center + Vec3f(s.radius)};
}
Bounds3f primBounds(const Cylinder& c) { return cylinderBounds(c); }

bool primHit(const Sphere& s, Vec3f o, Vec3f d, Float tMax, Float& t) {
    return intersectSphere(o, d, tMax, s.center, s.radius, t);
}
bool primHit(const Cylinder& c, Vec3f o, Vec3f d, Float tMax, Float& t) {
    return intersectCylinder(o, d, tMax, c.base, c.axis, c.radius, c.length, t);
}

/// Outward normal at a hit point (only its direction matters to Embree).
Vec3f primNormal(const Sphere& s, Vec3f p) { return p - s.center; }
Vec3f primNormal(const Cylinder& c, Vec3f p) {
    const Vec3f q = p - c.base;
    return q - c.axis * dot(q, c.axis);
}

template <class Prim>
void userBounds(const RTCBoundsFunctionArguments* args) {
    const Prim& prim = static_cast<const Prim*>(args->geometryUserPtr)[args->primID];
    const Bounds3f bb = primBounds(prim);
    RTCBounds* b = args->bounds_o;
    b->lower_x = bb.lo.x;
    b->lower_y = bb.lo.y;
    b->lower_z = bb.lo.z;
    b->upper_x = bb.hi.x;
    b->upper_y = bb.hi.y;
    b->upper_z = bb.hi.z;
}

/// Hit distance of lane i against the primitive, or a negative value for a miss.
template <class Prim>
float userHit(const Prim& prim, RTCRayN* ray, unsigned N, unsigned i) {
    const Vec3f o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const Vec3f d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    Float t;
    if (!primHit(prim, o, d, RTCRayN_tfar(ray, N, i), t)) return -1;
    return t > RTCRayN_tnear(ray, N, i) ? t : -1;
}

template <class Prim>
void userIntersect(const RTCIntersectFunctionNArguments* args) {
    const Prim& prim = static_cast<const Prim*>(args->geometryUserPtr)[args->primID];
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const float t = userHit(prim, ray, args->N, i);
        if (t < 0) continue;
        RTCRayN_tfar(ray, args->N, i) = t;
        const Vec3f o(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                      RTCRayN_org_z(ray, args->N, i));
        const Vec3f d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i),
                      RTCRayN_dir_z(ray, args->N, i));
        const Vec3f n = primNormal(prim, o + d * t);
        RTCHitN_Ng_x(hit, args->N, i) = n.x;
        RTCHitN_Ng_y(hit, args->N, i) = n.y;
        RTCHitN_Ng_z(hit, args->N, i) = n.z;
        RTCHitN_u(hit, args->N, i) = 0;
        RTCHitN_v(hit, args->N, i) = 0;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
    }
}

template <class Prim>
void userOccluded(const RTCOccludedFunctionNArguments* args) {
    const Prim& prim = static_cast<const Prim*>(args->geometryUserPtr)[args->primID];
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        if (userHit(prim, args->ray, args->N, i) >= 0)
            RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
}

/// Embree accepts hits with t <= tfar; the largest float below tMax makes the interval open.
/// Writes lane k of a ray record, single (RTCRay, k = 0) or packet (RTCRay4/8/16).
template <class R>
void setRayLane(R& r, int k, const Ray& ray) {
    if constexpr (std::is_same_v<R, RTCRay>) {
        r.org_x = ray.o.x, r.org_y = ray.o.y, r.org_z = ray.o.z, r.tnear = 0;
        r.dir_x = ray.d.x, r.dir_y = ray.d.y, r.dir_z = ray.d.z, r.time = 0;
        r.tfar = nextFloatTowardZero(ray.tMax), r.mask = ~0u, r.id = 0, r.flags = 0;
    } else {
        r.org_x[k] = ray.o.x, r.org_y[k] = ray.o.y, r.org_z[k] = ray.o.z, r.tnear[k] = 0;
        r.dir_x[k] = ray.d.x, r.dir_y[k] = ray.d.y, r.dir_z[k] = ray.d.z, r.time[k] = 0;
        r.tfar[k] = nextFloatTowardZero(ray.tMax), r.mask[k] = ~0u, r.id[k] = 0, r.flags[k] = 0;
    }
}

/// caustica's Hit for Embree's answer (geomID != RTC_INVALID_GEOMETRY_ID).
Hit toHit(const EmbreeIntersector& it, float tfar, unsigned geomID, unsigned primID, float u, float v) {
    Hit hit;
    hit.t = tfar;
    if (geomID == kTriangleGeomId || geomID >= kSecondTriangleRunGeomId) {
        const uint32_t run = geomID == kTriangleGeomId ? 0 : geomID - kSecondTriangleRunGeomId + 1;
        hit.primId = (it.triangleRunFirst ? it.triangleRunFirst[run] : 0) + primID;
        hit.b1 = u;
        hit.b2 = v;
    } else {
        hit.primId = (geomID == kSphereGeomId ? it.numTriangles : it.firstCylinder) + primID;
    }
    return hit;
}

// ---- spheres and cylinders tested directly (EmbreeSceneOptions::directPrimitives) ----

/// The closest of the intersector's direct parallelograms (when `quads`), spheres and cylinders
/// hit with t in (0, tMax), written to `hit`; false (hit unchanged) if none is. Tested before
/// Embree's query, whose tfar then becomes that t, so Embree culls what lies beyond and keeps a
/// triangle only if it is nearer. tMax is Embree's tfar for the ray, as a user geometry's
/// callback would get it. Parallelograms first, then spheres, then cylinders, each only if
/// nearer than the nearest so far (the packets' order too).
bool closestDirectHit(const EmbreeIntersector& it, const Ray& ray, Float tMax, Hit& hit, bool quads = true) {
    bool found = false;
    Float t, u, v;
    for (uint32_t i = 0; quads && i < it.numDirectQuads; ++i) {
        if (intersectParallelogram<float>(ray.o, ray.d, tMax, it.directQuads[i], t, u, v)) {
            tMax = t;
            hit = parallelogramHit(it.directQuads[i], t, u, v);
            found = true;
        }
    }
    for (uint32_t i = 0; i < it.numDirectSpheres; ++i) {
        if (primHit(it.directSpheres[i], ray.o, ray.d, tMax, t)) {
            tMax = t;
            hit = Hit{t, it.numTriangles + i};
            found = true;
        }
    }
    for (uint32_t i = 0; i < it.numDirectCylinders; ++i) {
        if (primHit(it.directCylinders[i], ray.o, ray.d, tMax, t)) {
            tMax = t;
            hit = Hit{t, it.firstCylinder + i};
            found = true;
        }
    }
    return found;
}

/// Whether any direct parallelogram (when `quads`), sphere or cylinder is hit with t in (0, tMax).
bool anyDirectHit(const EmbreeIntersector& it, const Ray& ray, Float tMax, bool quads = true) {
    Float t, u, v;
    for (uint32_t i = 0; quads && i < it.numDirectQuads; ++i)
        if (intersectParallelogram<float>(ray.o, ray.d, tMax, it.directQuads[i], t, u, v)) return true;
    for (uint32_t i = 0; i < it.numDirectSpheres; ++i)
        if (primHit(it.directSpheres[i], ray.o, ray.d, tMax, t)) return true;
    for (uint32_t i = 0; i < it.numDirectCylinders; ++i)
        if (primHit(it.directCylinders[i], ray.o, ray.d, tMax, t)) return true;
    return false;
}

/// Whether direct primitives are left to test ray by ray after the parallelograms' lanes (when
/// `quadsDone`): spheres or cylinders, or parallelograms not tested in lanes.
bool otherDirectPrimitives(const EmbreeIntersector& it, bool quadsDone) {
    return it.numDirectSpheres + it.numDirectCylinders > 0 || (!quadsDone && it.numDirectQuads > 0);
}

/// Whether the intersector's direct primitives are one sphere and nothing else (the bundled
/// scenes' case), which the packet queries test four lanes at a time (directSphereLanes).
bool oneDirectSphere(const EmbreeIntersector& it) {
    return CA_SPHERE_LANES && it.numDirectSpheres == 1 && it.numDirectCylinders == 0;
}

#if CA_SPHERE_LANES
/// The one direct sphere against the valid lanes [0, m) of packet `r` (fillPacket's; W a multiple
/// of 4), four lanes per SSE test: where lane k hits (before r.tfar[k]), hitT[k] is its t and bit
/// k of the result is set. The lanes get what closestDirectHit and anyDirectHit give their rays:
/// intersectSphere4 is intersectSphere to the bit, and the packet holds the rays' own floats.
template <int W, class R>
uint32_t directSphereLanes(const EmbreeIntersector& it, const R& r, const int (&valid)[W], int m, float (&hitT)[W]) {
    static_assert(W % 4 == 0, "packets of 4, 8 or 16 lanes");
    const Sphere& s = it.directSpheres[0];
    uint32_t hits = 0;
    for (int k0 = 0; k0 < m; k0 += 4) {
        const RayLanes4 lanes{_mm_loadu_ps(r.org_x + k0), _mm_loadu_ps(r.org_y + k0), _mm_loadu_ps(r.org_z + k0),
                              _mm_loadu_ps(r.dir_x + k0), _mm_loadu_ps(r.dir_y + k0), _mm_loadu_ps(r.dir_z + k0),
                              _mm_loadu_ps(r.tfar + k0)};
        float t[4];
        uint32_t mask = intersectSphere4(lanes, s.center, s.radius, t);
        for (; mask != 0; mask &= mask - 1) {
            const int k = k0 + __builtin_ctz(mask);
            if (k >= m || !valid[k]) continue;
            hitT[k] = t[k - k0];
            hits |= 1u << k;
        }
    }
    return hits;
}
#else
template <int W, class R>
uint32_t directSphereLanes(const EmbreeIntersector&, const R&, const int (&)[W], int, float (&)[W]) {
    return 0;  // never called: oneDirectSphere is false
}
#endif

#if CA_FLOAT4_SSE
/// The direct parallelograms against the valid lanes [0, m) of packet `r` (W a multiple of 4),
/// four lanes per test, in closestDirectHit's order: where lane k hits one before r.tfar[k],
/// r.tfar[k] becomes the nearest hit's t, hit[k] that hit, and bit k of the result is set.
/// intersectParallelogram<Float4> gives each lane the float form's bits, so the lanes get what
/// the single-ray queries give their rays.
template <int W, class R>
uint32_t directQuadLanes(const EmbreeIntersector& it, R& r, const int (&valid)[W], int m, Hit (&hit)[W]) {
    static_assert(W % 4 == 0, "packets of 4, 8 or 16 lanes");
    uint32_t hits = 0;
    for (int k0 = 0; k0 < m; k0 += 4) {
        const Vec3F4 o{Float4::loadUnaligned(r.org_x + k0), Float4::loadUnaligned(r.org_y + k0),
                       Float4::loadUnaligned(r.org_z + k0)};
        const Vec3F4 d{Float4::loadUnaligned(r.dir_x + k0), Float4::loadUnaligned(r.dir_y + k0),
                       Float4::loadUnaligned(r.dir_z + k0)};
        const bool live[4] = {k0 < m && valid[k0] != 0, k0 + 1 < m && valid[k0 + 1] != 0,
                              k0 + 2 < m && valid[k0 + 2] != 0, k0 + 3 < m && valid[k0 + 3] != 0};
        const Mask4 lanes = lane::maskOf(live);
        if (!lane::any(lanes)) continue;
        Float4 tMax = Float4::loadUnaligned(r.tfar + k0), bestU = Float4::broadcast(0), bestV = bestU;
        Index4 best;
        Mask4 found = lane::none<Float4>();
        for (uint32_t i = 0; i < it.numDirectQuads; ++i) {
            Float4 t, u, v;
            const Mask4 h = intersectParallelogram<Float4>(o, d, tMax, it.directQuads[i], t, u, v) & lanes;
            if (!lane::any(h)) continue;
            tMax = lane::select(h, t, tMax);
            bestU = lane::select(h, u, bestU);
            bestV = lane::select(h, v, bestV);
            for (uint32_t b = h.bits(); b != 0; b &= b - 1) best.k[__builtin_ctz(b)] = i;
            found = found | h;
        }
        for (uint32_t b = found.bits(); b != 0; b &= b - 1) {
            const int j = __builtin_ctz(b), k = k0 + j;
            r.tfar[k] = tMax[j];
            hit[k] = parallelogramHit(it.directQuads[best.k[j]], tMax[j], bestU[j], bestV[j]);
            hits |= 1u << k;
        }
    }
    return hits;
}
#endif

// ---- packets: Embree's packet types and calls by width ----

template <class RH, class R, void (*Intersect)(const int*, RTCScene, RTCIntersectContext*, RH*),
          void (*Occluded)(const int*, RTCScene, RTCIntersectContext*, R*)>
struct PacketCalls {
    using RayHit = RH;
    using RayT = R;
    static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RH* r) { Intersect(v, s, c, r); }
    static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, R* r) { Occluded(v, s, c, r); }
};
template <int W>
struct Packet;
template <>
struct Packet<4> : PacketCalls<RTCRayHit4, RTCRay4, rtcIntersect4, rtcOccluded4> {};
template <>
struct Packet<8> : PacketCalls<RTCRayHit8, RTCRay8, rtcIntersect8, rtcOccluded8> {};
template <>
struct Packet<16> : PacketCalls<RTCRayHit16, RTCRay16, rtcIntersect16, rtcOccluded16> {};

/// Fills the lanes of one packet from rays[0..m) and the valid mask: a lane is traced when it
/// holds a ray with tMax > 0 (the single-ray queries answer the others "no hit" without Embree);
/// the other lanes hold a harmless ray so that no lane is left uninitialised.
template <int W, class R>
void fillPacket(R& r, int (&valid)[W], int m, const Ray* const* rays) {
    for (int k = 0; k < W; ++k) {
        const bool live = k < m && rays[k]->tMax > 0;
        valid[k] = live ? -1 : 0;
        setRayLane(r, k, live ? *rays[k] : Ray{Vec3f(0), Vec3f(0, 0, 1), 0});
    }
}

/// f(context, first, m) for the packets [first, first + m) of n rays, m <= W.
template <int W, class F>
void forEachPacket(int n, F&& f, bool coherent = false) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (coherent) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int first = 0; first < n; first += W) f(context, first, std::min(W, n - first));
}

template <int W>
void intersectPackets(const EmbreeIntersector& it, int n, const Ray* const* rays, Hit* const* hits,
                      uint32_t* found, bool coherent) {
    forEachPacket<W>(n, [&](RTCIntersectContext& context, int first, int m) {
        alignas(64) int valid[W];
        alignas(64) typename Packet<W>::RayHit rh;
        fillPacket<W>(rh.ray, valid, m, rays + first);
        for (int k = 0; k < W; ++k) {
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        Hit direct[W];
        bool directFound[W] = {};
        bool quadsDone = false;  // the direct parallelograms tested in lanes already
#if CA_FLOAT4_SSE
        if (it.numDirectQuads > 0) {
            for (uint32_t lanes = directQuadLanes<W>(it, rh.ray, valid, m, direct); lanes != 0; lanes &= lanes - 1)
                directFound[__builtin_ctz(lanes)] = true;
            quadsDone = true;
        }
#endif
        if (oneDirectSphere(it)) {
            float t[W];
            for (uint32_t lanes = directSphereLanes<W>(it, rh.ray, valid, m, t); lanes != 0; lanes &= lanes - 1) {
                const int k = __builtin_ctz(lanes);
                direct[k] = Hit{t[k], it.numTriangles};
                directFound[k] = true;
                rh.ray.tfar[k] = t[k];
            }
        } else if (otherDirectPrimitives(it, quadsDone)) {
            for (int k = 0; k < m; ++k) {
                if (!valid[k]) continue;
                if (closestDirectHit(it, *rays[first + k], rh.ray.tfar[k], direct[k], !quadsDone)) {
                    directFound[k] = true;
                    rh.ray.tfar[k] = direct[k].t;
                }
            }
        }
        Packet<W>::intersect(valid, it.scene, &context, &rh);
        for (int k = 0; k < m; ++k) {
            const bool hit = valid[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
            found[first + k] = hit || directFound[k];
            *hits[first + k] = hit              ? toHit(it, rh.ray.tfar[k], rh.hit.geomID[k], rh.hit.primID[k],
                                                        rh.hit.u[k], rh.hit.v[k])
                               : directFound[k] ? direct[k]
                                                : Hit{};
        }
    }, coherent);
}

/// Lanes whose bit is set in `lanes` are occluded by a direct primitive: marked in directHit and
/// left out of Embree's query (valid 0). Returns whether any lane of [0, m) is still to be traced.
template <int W>
bool markOccluded(uint32_t lanes, int m, int (&valid)[W], bool (&directHit)[W]) {
    bool anyLeft = false;
    for (int k = 0; k < m; ++k) {
        directHit[k] = directHit[k] || ((lanes >> k) & 1u);
        if (directHit[k]) valid[k] = 0;
        anyLeft = anyLeft || valid[k];
    }
    return anyLeft;
}

template <int W>
void occludedPackets(const EmbreeIntersector& it, int n, const Ray* const* rays, uint32_t* occluded) {
    forEachPacket<W>(n, [&](RTCIntersectContext& context, int first, int m) {
        alignas(64) int valid[W];
        alignas(64) typename Packet<W>::RayT r;
        fillPacket<W>(r, valid, m, rays + first);
        bool directHit[W] = {};  // such a lane is occluded already: Embree skips it
        bool anyLeft = true;
        bool quadsDone = false;  // the direct parallelograms tested in lanes already
#if CA_FLOAT4_SSE
        if (it.numDirectQuads > 0) {
            Hit unused[W];
            anyLeft = markOccluded<W>(directQuadLanes<W>(it, r, valid, m, unused), m, valid, directHit);
            quadsDone = true;
        }
#endif
        if (oneDirectSphere(it)) {
            float t[W];
            anyLeft = markOccluded<W>(directSphereLanes<W>(it, r, valid, m, t), m, valid, directHit);
        } else if (otherDirectPrimitives(it, quadsDone)) {
            anyLeft = false;
            for (int k = 0; k < m; ++k) {
                if (!valid[k]) continue;
                directHit[k] = anyDirectHit(it, *rays[first + k], r.tfar[k], !quadsDone);
                if (directHit[k]) valid[k] = 0;
                anyLeft = anyLeft || valid[k];
            }
        }
        if (anyLeft) Packet<W>::occluded(valid, it.scene, &context, &r);
        for (int k = 0; k < m; ++k) occluded[first + k] = directHit[k] || (valid[k] && r.tfar[k] < 0);
    });
}

/// Rays per Embree packet call: the widest packet Embree runs natively on this CPU (16 with
/// AVX-512, 8 with AVX2, 4 with SSE), single rays without. On this project's AVX-512 VM 16-wide
/// packets are 4-7% faster than 4-wide for the path tracer and about 9% for the photon pass
/// (docs/PERFORMANCE.md, 2026-11-27 evening); an earlier measurement under a load of 8-14, before
/// Embree shared the scene's arrays, had found them slower.
constexpr int kPreferredPacketWidth = 16;

/// The widest packet up to `maxWidth` that Embree runs natively on this CPU (its ISA), or 1.
int widestNativePacket(RTCDevice device, int maxWidth) {
    const std::pair<int, RTCDeviceProperty> native[] = {{16, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED},
                                                        {8, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED},
                                                        {4, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED}};
    for (const auto& [width, property] : native)
        if (width <= maxWidth && rtcGetDeviceProperty(device, property)) return width;
    return 1;
}

static_assert(sizeof(Vec3f) == 12 && alignof(Vec3f) % 4 == 0, "Embree's RTC_FORMAT_FLOAT3 layout");
static_assert(sizeof(Vec3u) == 12 && alignof(Vec3u) % 4 == 0, "Embree's RTC_FORMAT_UINT3 layout");

}  // namespace

bool sharesVertexArray(const std::vector<Vec3f>& positions) {
    return positions.capacity() > positions.size();
}

void EmbreeScene::takeDirectParallelograms(const Scene& scene, uint32_t limit) {
    directQuads_ = directParallelograms(scene, limit);
    if (directQuads_.empty()) return;
    std::vector<bool> direct(scene.triangles.size(), false);
    for (const PreparedParallelogram& q : directQuads_) direct[q.mesh.first] = direct[q.mesh.second] = true;
    runFirst_.clear();
    runCount_.clear();
    for (uint32_t t = 0; t < uint32_t(scene.triangles.size()); ++t) {
        if (direct[t]) continue;
        if (runFirst_.empty() || runFirst_.back() + runCount_.back() != t) {
            runFirst_.push_back(t);
            runCount_.push_back(0);
        }
        ++runCount_.back();
    }
}

EmbreeIntersector EmbreeScene::intersector() const {
    EmbreeIntersector it;
    it.scene = scene_;
    it.numTriangles = numTriangles_;
    it.firstCylinder = firstCylinder_;
    it.packetWidth = packetWidth_;
    it.directSpheres = directSpheres_;
    it.numDirectSpheres = numDirectSpheres_;
    it.directCylinders = directCylinders_;
    it.numDirectCylinders = numDirectCylinders_;
    if (!directQuads_.empty()) {
        it.directQuads = directQuads_.data();
        it.numDirectQuads = uint32_t(directQuads_.size());
        it.triangleRunFirst = runFirst_.empty() ? nullptr : runFirst_.data();
    }
    return it;
}

uint32_t EmbreeScene::directParallelogramCount() const { return uint32_t(directQuads_.size()); }

void EmbreeScene::addTriangleRun(const Scene& scene, uint32_t first, uint32_t count, unsigned geomId) {
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    check("rtcNewGeometry(triangle)");
    // The index triples [first, first + count) are shared as they are. Embree reads a vertex with
    // a 16-byte load, 4 bytes past its end (it even reads the last vertex's 4 bytes at once,
    // buffer.h checkPadding16), so the positions are shared only when the vector's spare capacity
    // holds those 4 bytes; else they are copied into a buffer Embree pads itself (the geometry
    // then owns that copy).
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, scene.triangles.data(),
                               size_t(first) * sizeof(Vec3u), sizeof(Vec3u), count);
    if (sharesVertices_) {
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                   scene.positions.data(), 0, sizeof(Vec3f), scene.positions.size());
    } else {
        void* vertices = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                 sizeof(Vec3f), scene.positions.size());
        if (vertices)
            std::memcpy(vertices, scene.positions.data(), scene.positions.size() * sizeof(Vec3f));
    }
    check("triangle buffers");
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, geomId);
    rtcReleaseGeometry(geom);
    check("triangle geometry");
}

EmbreeScene::EmbreeScene(const Scene& scene, const EmbreeSceneOptions& options)
    : numTriangles_(uint32_t(scene.triangles.size())),
      firstCylinder_(uint32_t(scene.triangles.size() + scene.spheres.size())) {
    const auto start = std::chrono::steady_clock::now();
    isa_ = resolveEmbreeIsa(options.isa, hostCpuModel());
    device_ = rtcNewDevice(embreeDeviceConfig(isa_).c_str());
    if (!device_)
        throw Error(std::string("Embree: cannot create device: ") +
                    errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(device_, errorCallback, &lastMessage_);
    nativePacketWidth_ = widestNativePacket(device_, 16);
    packetWidth_ = widestNativePacket(device_, kPreferredPacketWidth);
    try {
        scene_ = rtcNewScene(device_);
        check("rtcNewScene");
        rtcSetSceneFlags(scene_, options.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
        takeDirectParallelograms(scene, options.directParallelograms);
        // addTriangleRun's choice, made once for all runs (false when Embree is given no triangle).
        sharesVertices_ = numTriangles_ > 2 * directQuads_.size() && sharesVertexArray(scene.positions);
        if (directQuads_.empty()) {
            if (numTriangles_ > 0) addTriangleRun(scene, 0, numTriangles_, kTriangleGeomId);
        } else {
            // Few runs (at most one more than parallelograms); when the vertices are not shared,
            // each run's geometry holds its own copy of them.
            for (size_t r = 0; r < runFirst_.size(); ++r)
                addTriangleRun(scene, runFirst_[r], runCount_[r],
                               r == 0 ? kTriangleGeomId : unsigned(kSecondTriangleRunGeomId + r - 1));
        }
        if (scene.spheres.size() + scene.cylinders.size() <= options.directPrimitives) {
            directSpheres_ = scene.spheres.data();
            numDirectSpheres_ = uint32_t(scene.spheres.size());
            directCylinders_ = scene.cylinders.data();
            numDirectCylinders_ = uint32_t(scene.cylinders.size());
        } else {
            if (!scene.spheres.empty()) addUserGeometry(scene.spheres, kSphereGeomId, "sphere geometry");
            if (!scene.cylinders.empty())
                addUserGeometry(scene.cylinders, kCylinderGeomId, "cylinder geometry");
        }
        rtcCommitScene(scene_);
        check("rtcCommitScene");
    } catch (...) {
        release();
        throw;
    }
    buildMilliseconds_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

template <class Prim>
void EmbreeScene::addUserGeometry(const std::vector<Prim>& prims, unsigned geomId,
                                  const char* what) {
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    check("rtcNewGeometry(user)");
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(prims.size()));
    rtcSetGeometryUserData(geom, const_cast<Prim*>(prims.data()));
    rtcSetGeometryBoundsFunction(geom, userBounds<Prim>, nullptr);
    rtcSetGeometryIntersectFunction(geom, userIntersect<Prim>);
    rtcSetGeometryOccludedFunction(geom, userOccluded<Prim>);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, geomId);
    rtcReleaseGeometry(geom);
    check(what);
}

EmbreeScene::~EmbreeScene() { release(); }

void EmbreeScene::release() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
    scene_ = nullptr;
    device_ = nullptr;
}

void EmbreeScene::check(const char* what) {
    const RTCError code = rtcGetDeviceError(device_);
    if (code == RTC_ERROR_NONE) return;
    throw Error(std::string("Embree: ") + what +
                " failed: " + (lastMessage_.empty() ? errorName(code) : lastMessage_));
}

bool EmbreeIntersector::intersect(const Ray& ray, Hit& hit) const {
    if (!scene || !(ray.tMax > 0)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayHit;
    setRayLane(rayHit.ray, 0, ray);
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    Hit direct;
    const bool directFound = hasDirectPrimitives() && closestDirectHit(*this, ray, rayHit.ray.tfar, direct);
    if (directFound) rayHit.ray.tfar = direct.t;
    rtcIntersect1(scene, &context, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        if (directFound) hit = direct;
        return directFound;
    }
    hit = toHit(*this, rayHit.ray.tfar, rayHit.hit.geomID, rayHit.hit.primID, rayHit.hit.u, rayHit.hit.v);
    return true;
}

bool EmbreeIntersector::occluded(const Ray& ray) const {
    if (!scene || !(ray.tMax > 0)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r;
    setRayLane(r, 0, ray);
    if (hasDirectPrimitives() && anyDirectHit(*this, ray, r.tfar)) return true;
    rtcOccluded1(scene, &context, &r);
    return r.tfar < 0;
}

void EmbreeIntersector::intersectPacket(int n, const Ray* const* rays, Hit* const* hits, uint32_t* found,
                                        bool coherent) const {
    switch (scene ? packetWidth : 1) {
    case 16: return intersectPackets<16>(*this, n, rays, hits, found, coherent);
    case 8: return intersectPackets<8>(*this, n, rays, hits, found, coherent);
    case 4: return intersectPackets<4>(*this, n, rays, hits, found, coherent);
    default: return intersectEach(*this, n, rays, hits, found);
    }
}

void EmbreeIntersector::occludedPacket(int n, const Ray* const* rays, uint32_t* occluded) const {
    switch (scene ? packetWidth : 1) {
    case 16: return occludedPackets<16>(*this, n, rays, occluded);
    case 8: return occludedPackets<8>(*this, n, rays, occluded);
    case 4: return occludedPackets<4>(*this, n, rays, occluded);
    default: return occludedEach(*this, n, rays, occluded);
    }
}

}  // namespace caustica
