// interaction.h — what a ray hit: position, normals, uv, the surface's dp/du and dp/dv, and the
// shape's material and emitter. The BSDFs' local frame is shadingFrame(si), built from the shading
// normal and dp/du as Mitsuba 3 does (SurfaceInteraction::initialize_sh_frame).
#pragma once

#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

namespace caustica {

struct SurfaceInteraction {
    Vec3f p;
    Vec3f ng;        // geometric normal, on the shape's outside (flip_normals applied)
    Vec3f ns;        // shading normal, same hemisphere as ng
    Vec2f uv;
    Vec3f dpdu, dpdv;  // position partials along uv, world space; zero = unknown (Frame(ns) is used)
    uint32_t primId = kNoPrimitive;
    uint32_t shape = 0;
    TextureView textures;  // the scene's textures, for BSDF parameters (texture.h)
};

/// The axes s, t of Mitsuba's shading frame around the unit shading normal ns: s = dp/du made
/// orthogonal to ns (Gram–Schmidt), t = ns × s; without a usable dp/du, Mitsuba's
/// coordinate_system(ns) (Frame(ns)). Generic over the lane type F (util/lane.h).
template <LaneFloat F>
CA_HD_FORCE_INLINE void shadingFrameAxes(const Vec3Of<F>& ns, const Vec3Of<F>& dpdu, Vec3Of<F>& s, Vec3Of<F>& t) {
    const Vec3Of<F> g = dpdu - ns * dot(ns, dpdu);
    const F len2 = dot(g, g);
    const MaskOf<F> usable = (len2 > Float(1e-30)) & (len2 < Float(1e30));
    Vec3Of<F> fs{}, ft{};
    if (!lane::all(usable)) orthonormalBasis<F>(ns, fs, ft);
    const Vec3Of<F> gs = g * (1 / lane::sqrt(len2));
    s = lane::select<F>(usable, gs, fs);
    t = lane::select<F>(usable, cross(ns, gs), ft);
}

/// Mitsuba's shading frame at si (shadingFrameAxes of si.ns and si.dpdu).
CA_HD_INLINE Frame shadingFrame(const SurfaceInteraction& si) {
    Frame f;
    f.n = si.ns;
    shadingFrameAxes<float>(si.ns, si.dpdu, f.s, f.t);
    return f;
}

/// Mitsuba's cylinder at the point si.p (reprojected onto the surface): uv = (φ / 2π, h / length),
/// dp/du = 2π r (tangent), dp/dv = length · axis, normal away from the axis unless flipped.
CA_HD_INLINE void cylinderInteraction(const Cylinder& c, bool flip, SurfaceInteraction& si) {
    const Vec3f q = si.p - c.base;
    const Float h = dot(q, c.axis);
    const Vec3f yAxis = cross(c.axis, c.xAxis);
    const Float x = dot(q, c.xAxis), y = dot(q, yAxis);
    Float phi = std::atan2(y, x);
    if (phi < 0) phi += 2 * kPi;
    const Float cosPhi = std::cos(phi), sinPhi = std::sin(phi);
    Vec3f n = c.xAxis * cosPhi + yAxis * sinPhi;
    si.p = c.base + c.axis * h + n * c.radius;
    si.uv = Vec2f(phi * kInv2Pi, h / c.length);
    si.dpdu = (yAxis * cosPhi - c.xAxis * sinPhi) * (2 * kPi * c.radius);
    si.dpdv = c.axis * c.length;
    if (flip) n = -n;
    si.ng = si.ns = n;
}

/// Mitsuba's sphere interaction at `si.p` (reprojected onto the surface): with l the hit in object
/// space (to_object, on the unit sphere), uv = (φ / 2π, θ / π) of l, dp/du = 2π to_world(−l.y,
/// l.x, 0), dp/dv = π to_world(l.z cosφ, l.z sinφ, −ρ), ρ = sqrt(l.x² + l.y²); dp/dv =
/// π to_world(1, 0, 0) at the poles (src/shapes/sphere.cpp, compute_surface_interaction).
/// `withUv` false leaves si.uv alone: nothing else needs φ and θ, whose atan2 and acos are most
/// of the cost of a sphere hit.
CA_HD_INLINE void sphereInteraction(const Sphere& s, bool flip, SurfaceInteraction& si, bool withUv = true) {
    Vec3f n = normalize(si.p - s.center);
    si.p = s.center + n * s.radius;
    const Vec3f l(dot(n, s.objectX), dot(n, s.objectY), dot(n, s.objectZ));
    if (withUv) {
        Float phi = std::atan2(l.y, l.x);
        if (phi < 0) phi += 2 * kPi;
        si.uv = Vec2f(phi * kInv2Pi, std::acos(clamp(l.z, Float(-1), Float(1))) * kInvPi);
    }
    const Float rho = std::sqrt(l.x * l.x + l.y * l.y);
    const Vec3f dv = rho > 0 ? Vec3f(l.z * l.x / rho, l.z * l.y / rho, -rho) : Vec3f(1, 0, 0);
    si.dpdu = (s.objectY * l.x - s.objectX * l.y) * (2 * kPi * s.radius);
    si.dpdv = (s.objectX * dv.x + s.objectY * dv.y + s.objectZ * dv.z) * (kPi * s.radius);
    if (flip) n = -n;
    si.ng = si.ns = n;
}

/// A mesh triangle's point at barycentrics (b1, b2) and its normals, as every hit on it and every
/// light sample on it sees them: the vertex indices, the edges p1 - p0 and p2 - p0, the point on
/// the surface, the unflipped face normal (for dp/du, dp/dv), and ng / ns with flip_normals
/// applied (for meshes with normals Mitsuba orients ng by ns). (The edges, not the vertices: the
/// fewer 12-byte fields g++ copies through the stack, the fewer loads wait on partial stores.)
template <class F>
struct LaneTrianglePoint {
    Vec3uOf<F> tri;
    Vec3Of<F> edge1, edge2;
    F b0;
    Vec3Of<F> p;
    Vec3Of<F> faceNormal;  // unflipped
    Vec3Of<F> ng, ns;      // flip_normals applied
};
using TrianglePoint = LaneTrianglePoint<float>;

/// trianglePoint generic over the lane type F: lane k is triangle primId[k] of a mesh with
/// vertex normals where hasNormals, flip_normals where flip.
template <LaneFloat F>
CA_HD_FORCE_INLINE LaneTrianglePoint<F> trianglePointOf(const SceneView& scene, const IndexOf<F>& primId,
                                                        MaskOf<F> hasNormals, MaskOf<F> flip, F b1, F b2) {
    LaneTrianglePoint<F> t;
    t.tri = lane::gather(scene.triangles, primId);
    // References for one lane, not copies: g++ copies a 12-byte Vec3f through general registers
    // and the stack, and the float loads that follow wait on those stores (store forwarding fails).
    const auto &p0 = lane::gather(scene.positions, t.tri.x), &p1 = lane::gather(scene.positions, t.tri.y),
               &p2 = lane::gather(scene.positions, t.tri.z);
    t.b0 = 1 - b1 - b2;
    t.p = p0 * t.b0 + p1 * b1 + p2 * b2;  // on the surface, not ray-distance rounded
    t.edge1 = p1 - p0;
    t.edge2 = p2 - p0;
    t.faceNormal = normalize(cross(t.edge1, t.edge2));
    t.ng = t.faceNormal;
    t.ns = t.ng;
    if (lane::any(hasNormals)) {
        const Vec3Of<F> n = lane::gatherWhere(hasNormals, scene.normals, t.tri.x) * t.b0 +
                            lane::gatherWhere(hasNormals, scene.normals, t.tri.y) * b1 +
                            lane::gatherWhere(hasNormals, scene.normals, t.tri.z) * b2;
        const MaskOf<F> shaded = hasNormals & (lengthSquared(n) > 0);
        if (lane::any(shaded)) {
            t.ns = lane::select<F>(shaded, normalize(n), t.ns);
            // Mitsuba orients the geometric normal by the shading normal for meshes with normals.
            t.ng = lane::select<F>(shaded, faceForward(t.ng, t.ns), t.ng);
        }
    }
    if (lane::any(flip)) {
        t.ng = lane::select<F>(flip, -t.ng, t.ng);
        t.ns = lane::select<F>(flip, -t.ns, t.ns);
    }
    return t;
}

CA_HD_INLINE TrianglePoint trianglePoint(const SceneView& scene, const Shape& shape, uint32_t primId, Float b1,
                                         Float b2) {
    return trianglePointOf<float>(scene, primId, shape.hasNormals, shape.flipNormals, b1, b2);
}

/// What computeInteraction finds at a mesh hit, generic over the lane type F (lane k: triangle
/// primId[k], of a mesh with vertex normals / flip_normals / uvs where the masks say so).
template <class F>
struct LaneTriangleSurface {
    Vec3Of<F> p, ng, ns, dpdu, dpdv;
    Vec2Of<F> uv;
};

template <LaneFloat F>
CA_HD_FORCE_INLINE LaneTriangleSurface<F> triangleSurface(const SceneView& scene, const IndexOf<F>& primId,
                                                          MaskOf<F> hasNormals, MaskOf<F> flip, MaskOf<F> hasUVs,
                                                          F b1, F b2) {
    const LaneTrianglePoint<F> t = trianglePointOf<F>(scene, primId, hasNormals, flip, b1, b2);
    LaneTriangleSurface<F> s{};
    s.p = t.p;
    s.ng = t.ng;
    s.ns = t.ns;
    // Mitsuba's mesh: dp/du, dp/dv from the uv parameterisation, else (or when the uv triangle
    // is degenerate) coordinate_system of the unflipped face normal (built only then).
    s.uv = Vec2Of<F>{b1, b2};
    MaskOf<F> uvPartials = lane::none<F>();
    if (lane::any(hasUVs)) {
        const auto &uv0 = lane::gatherWhere(hasUVs, scene.uvs, t.tri.x),
                   &uv1 = lane::gatherWhere(hasUVs, scene.uvs, t.tri.y),
                   &uv2 = lane::gatherWhere(hasUVs, scene.uvs, t.tri.z);
        s.uv = lane::select<F>(hasUVs, uv0 * t.b0 + uv1 * b1 + uv2 * b2, s.uv);
        const Vec2Of<F> duv0 = uv1 - uv0, duv1 = uv2 - uv0;
        const F det = duv0.x * duv1.y - duv0.y * duv1.x;
        uvPartials = hasUVs & (det != lane::splat<F>(0));
        if (lane::any(uvPartials)) {
            const F invDet = 1 / det;
            s.dpdu = (t.edge1 * duv1.y - t.edge2 * duv0.y) * invDet;
            s.dpdv = (t.edge2 * duv0.x - t.edge1 * duv1.x) * invDet;
        }
    }
    if (!lane::all(uvPartials)) {
        Vec3Of<F> fs, ft;
        orthonormalBasis<F>(t.faceNormal, fs, ft);
        s.dpdu = lane::select<F>(uvPartials, s.dpdu, fs);
        s.dpdv = lane::select<F>(uvPartials, s.dpdv, ft);
    }
    return s;
}

/// Whether a render of `scene` reads SurfaceInteraction::uv: only BSDF textures (bump and normal
/// maps included) do, so a scene without textures needs none (the uv AOV asks for it itself).
CA_HD_INLINE bool sceneReadsUv(const SceneView& scene) { return scene.textures.size() > 0; }

/// Fills the interaction for a valid hit of `ray`. `withUv` false: a sphere's si.uv is left (0, 0)
/// (sphereInteraction); every other field, and every other shape's uv, is the same.
CA_HD_INLINE SurfaceInteraction computeInteraction(const SceneView& scene, const Ray& ray, const Hit& hit,
                                                   bool withUv) {
    SurfaceInteraction si;
    si.primId = hit.primId;
    si.textures = scene.textureView();
    si.p = ray.o + ray.d * hit.t;
    if (hit.primId < scene.numTriangles()) {
        si.shape = scene.triangleShape[hit.primId];
        const Shape& shape = scene.shapes[si.shape];
        const LaneTriangleSurface<float> t = triangleSurface<float>(
            scene, hit.primId, shape.hasNormals, shape.flipNormals, shape.hasUVs, hit.b1, hit.b2);
        si.p = t.p;
        si.ng = t.ng;
        si.ns = t.ns;
        si.uv = t.uv;
        si.dpdu = t.dpdu;
        si.dpdv = t.dpdv;
    } else if (hit.primId >= scene.firstCylinder()) {
        const Cylinder& c = scene.cylinders[hit.primId - scene.firstCylinder()];
        si.shape = c.shape;
        cylinderInteraction(c, scene.shapes[c.shape].flipNormals, si);
    } else {
        const Sphere& s = scene.spheres[hit.primId - scene.numTriangles()];
        si.shape = s.shape;
        sphereInteraction(s, scene.shapes[s.shape].flipNormals, si, withUv);
    }
    return si;
}

/// The interaction with uv where the scene reads it (sceneReadsUv).
CA_HD_INLINE SurfaceInteraction computeInteraction(const SceneView& scene, const Ray& ray, const Hit& hit) {
    return computeInteraction(scene, ray, hit, sceneReadsUv(scene));
}

}  // namespace caustica
