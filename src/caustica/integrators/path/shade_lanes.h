// shade_lanes.h — a CPU thread's shade stage four paths at a time. shadeVertex (path_kernel.h) is
// the one description of a bounce; here it runs over LaneVertex4, whose F is Float4: four paths'
// vertices side by side in SSE registers, each lane given the bits the scalar instantiation gives
// that path (every lane operation rounds as its scalar form, util/lane.h). The wavefront's CPU
// schedule gathers the queue entries it can take four at a time (shadeStageByFour) and shades the
// rest one by one through the same shadeVertex; a GPU thread always runs the scalar vertex.
//
// What a lane vertex can take today (diffuseQuadEligible): a hit on a triangle of a shape that
// emits nothing, below the maximum depth, whose BSDF is a plain diffuse one without textures
// or a twosided over two such (door-gap's walls), in a scene whose lights are all rectangles
// (allLightsAreQuads) — cornell-box's every bounce.
// Other BSDFs, emitters and light types are shaded per path. Host-only (SSE).
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/integrators/path/path_kernel.h"
#include "caustica/util/lane.h"

namespace caustica {

/// Whether every light of the scene is a parallelogram area light (Light::isQuad).
inline bool allLightsAreQuads(const SceneView& scene) {
    if (scene.lights.empty()) return false;
    for (const Light& l : scene.lights)
        if (l.type != LightType::Area || !l.isQuad) return false;
    return true;
}

/// Whether shadeDiffuseQuad4 can take this path's hit (see the file comment).
CA_HD_INLINE bool diffuseQuadEligible(const SceneView& scene, const PathState& path, const Hit& hit,
                                      const PathSettings& settings) {
    if (hit.primId >= scene.numTriangles()) return false;
    const Shape& shape = scene.shapes[scene.triangleShape[hit.primId]];
    if (shape.light >= 0 || path.depth + 1 >= maxDepthOf(settings)) return false;
    const auto plainDiffuse = [](const Bsdf& b) { return b.type == BsdfType::Diffuse && b.numTextures == 0; };
    const Bsdf& b = scene.bsdfs[shape.bsdf];
    if (b.type == BsdfType::TwoSided) return plainDiffuse(scene.bsdfs[b.front]) && plainDiffuse(scene.bsdfs[b.back]);
    return plainDiffuse(b);
}

#if CA_FLOAT4_SSE
namespace shade_lanes_detail {
inline Vec3F4 towards4(const Vec3F4& n, const Vec3F4& d) {  // n on d's side
    return lane::select<Float4>(dot(d, n) > 0, n, -n);
}
inline Float4 load4(const float (&v)[4]) { return Float4::fromLanes(v[0], v[1], v[2], v[3]); }
inline Vec3F4 load3(const Vec3f (&v)[4]) { return lane::fromLanes(v[0], v[1], v[2], v[3]); }
inline SpectrumF4 loadSpectrum(const Spectrum (&v)[4]) {
    return {Float4::fromLanes(v[0].r, v[1].r, v[2].r, v[3].r), Float4::fromLanes(v[0].g, v[1].g, v[2].g, v[3].g),
            Float4::fromLanes(v[0].b, v[1].b, v[2].b, v[3].b)};
}
}  // namespace shade_lanes_detail

struct LightSampleF4 {
    Vec3F4 p, n, wi;
    Float4 dist, pdf;
    SpectrumF4 Le;
    Mask4 delta;
};
struct BsdfSampleF4 {
    Vec3F4 wi;
    SpectrumF4 weight;
    Float4 pdf, eta;
    Mask4 delta;
};
template <>
struct LaneForm4<LightSample> {
    using Type = LightSampleF4;
};
template <>
struct LaneForm4<BsdfSample> {
    using Type = BsdfSampleF4;
};

namespace shade_lanes_detail {

/// A plain diffuse BSDF at four vertices: PreparedLeaf::evalPdfAlone / sampleAlone's operations
/// (bsdf.h) around the shared diffuse functions. The scalar path weighs its one leaf by 1 and sums
/// it onto zero; the `* one` and `zero +` below repeat that, so -0 and NaN come out as there.
struct DiffuseLanes4 {
    Vec3F4 s, t, n, woL;
    SpectrumF4 R;

    SpectrumF4 evalPdf(const Vec3F4& wi, Float4& pdf) const {
        const Float4 zero = Float4::broadcast(0), one = Float4::broadcast(1);
        const Vec3F4 wiL = frameToLocal<Float4>(s, t, n, wi);
        const SpectrumF4 e = bsdf_detail::diffuseEvalLocal<Float4>(R, woL, wiL);
        pdf = zero + bsdf_detail::diffusePdfLocal<Float4>(woL, wiL) * one;
        return {zero + (e.r * one) * one, zero + (e.g * one) * one, zero + (e.b * one) * one};
    }
    Mask4 sample(Float4, const Vec2F4& u, BsdfSampleF4& bs) const {
        const Float4 one = Float4::broadcast(1);
        Vec3F4 wiS;
        const Mask4 ok = bsdf_detail::diffuseSampleLocal<Float4>(woL, u, wiS, bs.pdf);
        bs.wi = frameToWorld<Float4>(s, t, n, wiS);
        bs.eta = one;
        bs.delta = lane::none<Float4>();
        const SpectrumF4 value = (R * one) * bs.pdf;
        bs.weight = value * (1 / bs.pdf);
        return ok & (bs.pdf > 0.0f);
    }
};
}  // namespace shade_lanes_detail

/// Four paths' vertices for shadeVertex (F = Float4), all eligible (diffuseQuadEligible, under
/// lights that are all rectangles): their surfaces (triangleSurface over lanes), throughputs,
/// η scales and ray directions in lanes. finish() writes the lanes back into the paths.
template <class Sampler>
struct LaneVertex4 {
    using F = Float4;
    const SceneView& scene;
    PathState* const* path;
    Sampler* const* sampler;
    ShadowRay* const* shadow;
    bool* hasShadow;
    Vec3F4 P, NG, NS, dpdu, D;
    SpectrumF4 B;
    Float4 eta;
    uint32_t depth[4];
    uint32_t shape[4];

    LaneVertex4(const SceneView& scene_, PathState* const* path_, const Hit* const* hit, Sampler* const* sampler_,
                ShadowRay* const* shadow_, bool* hasShadow_)
        : scene(scene_), path(path_), sampler(sampler_), shadow(shadow_), hasShadow(hasShadow_) {
        using namespace shade_lanes_detail;
        Index4 prim;
        bool normals[4], flip[4], uvs[4];
        float b1[4], b2[4], e[4];
        Vec3f d[4];
        Spectrum b[4];
        for (int k = 0; k < 4; ++k) {
            prim.k[k] = hit[k]->primId;
            shape[k] = scene.triangleShape[hit[k]->primId];
            const Shape& s = scene.shapes[shape[k]];
            normals[k] = s.hasNormals;
            flip[k] = s.flipNormals;
            uvs[k] = s.hasUVs;
            b1[k] = hit[k]->b1;
            b2[k] = hit[k]->b2;
            d[k] = path[k]->ray.d;
            b[k] = path[k]->throughput;
            e[k] = path[k]->etaScale;
            depth[k] = path[k]->depth;
            hasShadow[k] = false;
        }
        const LaneTriangleSurface<Float4> surface =
            triangleSurface<Float4>(scene, prim, lane::maskOf(normals), lane::maskOf(flip), lane::maskOf(uvs), load4(b1), load4(b2));
        P = surface.p, NG = surface.ng, NS = surface.ns, dpdu = surface.dpdu;
        D = load3(d);
        B = loadSpectrum(b);
        eta = load4(e);
    }

    Vec3F4 rayDirection() const { return D; }
    Mask4 emitterSeen(const PathSettings&) const { return lane::none<Float4>(); }  // eligible: no emitter
    SpectrumF4 emitted(const Vec3F4&) const { const Float4 z = Float4::broadcast(0); return {z, z, z}; }
    Float4 emissionWeight() const { return Float4::broadcast(0); }
    void addRadiance(Mask4, const SpectrumF4&) {}  // never called: no emitter is seen
    const SpectrumF4& throughput() const { return B; }
    Mask4 belowMaxDepth(const PathSettings& settings) const {
        bool b[4];
        for (int k = 0; k < 4; ++k) b[k] = depth[k] + 1 < maxDepthOf(settings);
        return lane::maskOf(b);
    }
    shade_lanes_detail::DiffuseLanes4 prepareBsdf(const Vec3F4& wo) const {
        shade_lanes_detail::DiffuseLanes4 bsdf;
        shadingFrameAxes<Float4>(NS, dpdu, bsdf.s, bsdf.t);
        // A twosided's lanes as resolve() (bsdf.h) takes them: where wo is below the shading
        // normal, the back child with the normal negated (s and t stay those of NS).
        const uint32_t below = (dot(wo, NS) < 0.0f).bits();
        Spectrum r[4];
        bool back[4];
        for (int k = 0; k < 4; ++k) {
            const Bsdf& b = scene.bsdfs[scene.shapes[shape[k]].bsdf];
            back[k] = b.type == BsdfType::TwoSided && ((below >> k) & 1u);
            r[k] = b.type != BsdfType::TwoSided ? b.reflectance : scene.bsdfs[back[k] ? b.back : b.front].reflectance;
        }
        bsdf.n = lane::select<Float4>(lane::maskOf(back), -NS, NS);
        bsdf.woL = frameToLocal<Float4>(bsdf.s, bsdf.t, bsdf.n, wo);
        bsdf.R = shade_lanes_detail::loadSpectrum(r);
        return bsdf;
    }
    Mask4 deltaBsdf() const { return lane::none<Float4>(); }  // eligible: diffuse
    Float4 get1D(Mask4 alive) {
        const uint32_t bits = alive.bits();
        float u[4];
        for (int k = 0; k < 4; ++k) u[k] = (bits >> k) & 1u ? sampler[k]->get1D() : 0.0f;
        return shade_lanes_detail::load4(u);
    }
    Vec2F4 get2D(Mask4 alive) {
        const uint32_t bits = alive.bits();
        Vec2f u[4];
        for (int k = 0; k < 4; ++k)
            if ((bits >> k) & 1u) u[k] = sampler[k]->get2D();
        return lane::fromLanes(u[0], u[1], u[2], u[3]);
    }
    Mask4 sampleLight(Float4 uSelect, const Vec2F4& uLight, LightSampleF4& ls) const {
        using namespace shade_lanes_detail;
        const uint32_t count = uint32_t(scene.lights.size());
        Vec3f corner[4], edgeU[4], edgeV[4], normal[4];
        Spectrum le[4];
        float area[4];
        for (int k = 0; k < 4; ++k) {
            const Light& l = scene.lights[min(uint32_t(uSelect[k] * Float(count)), count - 1)];
            corner[k] = l.quadCorner, edgeU[k] = l.quadEdgeU, edgeV[k] = l.quadEdgeV, normal[k] = l.quadNormal;
            le[k] = l.radiance;
            area[k] = l.area;
        }
        ls.p = light_detail::parallelogramPoint<Float4>(load3(corner), load3(edgeU), load3(edgeV), uLight);
        ls.n = load3(normal);
        const Float4 pdf = light_detail::areaToSolidAngle<Float4>(P, ls.p, ls.n, load4(area));
        ls.Le = loadSpectrum(le);
        ls.delta = lane::none<Float4>();  // a rectangle
        return light_detail::areaLightDirection<Float4>(P, ls.p, pdf, Float4::broadcast(Float(1) / Float(count)), ls.wi,
                                                        ls.dist, ls.pdf);
    }
    void setShadow(Mask4 lit, const LightSampleF4& ls, const SpectrumF4& contribution) {
        using namespace shade_lanes_detail;
        const Vec3F4 o = offsetRayOrigin(P, towards4(NG, ls.p - P));
        const Vec3F4 target = offsetRayOrigin(ls.p, towards4(ls.n, o - ls.p));  // a rectangle's normal is not zero
        const Vec3F4 d = target - o;
        const uint32_t bits = lit.bits();
        for (int k = 0; k < 4; ++k) {
            if (!((bits >> k) & 1u)) continue;
            shadow[k]->ray = Ray{lane::extract(o, k), lane::extract(d, k), 1 - 1e-4f};
            shadow[k]->contribution = lane::extract(contribution, k);
            hasShadow[k] = true;
        }
    }
    void advance(Mask4 alive, const BsdfSampleF4& bs) {
        using namespace shade_lanes_detail;
        B = lane::select<Float4>(alive, B * bs.weight, B);
        eta = lane::select(alive, eta * bs.eta, eta);
        const Vec3F4 o = offsetRayOrigin(P, towards4(NG, bs.wi));
        const uint32_t bits = alive.bits();
        for (int k = 0; k < 4; ++k) {
            if (!((bits >> k) & 1u)) continue;
            PathState& ps = *path[k];
            ps.prevBsdfPdf = bs.pdf[k];
            ps.prevBsdfDelta = false;
            ps.prevP = lane::extract(P, k);
            ps.ray = Ray{lane::extract(o, k), lane::extract(bs.wi, k), kInfinity};
            ++depth[k];
        }
    }
    Mask4 atLeastRrDepth(const PathSettings& settings) const {
        bool b[4];
        for (int k = 0; k < 4; ++k) b[k] = depth[k] >= uint32_t(settings.rrDepth);
        return lane::maskOf(b);
    }
    Float4 etaScale() const { return eta; }
    void scaleThroughput(Mask4 m, Float4 s) { B = lane::select<Float4>(m, B * s, B); }
    /// The lanes' throughput, η scale and depth back into the paths.
    void finish() {
        for (int k = 0; k < 4; ++k) {
            path[k]->throughput = lane::extract(B, k);
            path[k]->etaScale = eta[k];
            path[k]->depth = depth[k];
        }
    }
};

/// shadeHit of four eligible paths (diffuseQuadEligible, allLightsAreQuads), each with its own
/// hit and sampler: shadeVertex over a LaneVertex4. Returns the alive bits.
template <class Sampler>
inline uint32_t shadeDiffuseQuad4(const SceneView& scene, PathState* const path[4], const Hit* const hit[4],
                                  Sampler* const sampler[4], const PathSettings& settings, ShadowRay* const shadow[4],
                                  bool hasShadow[4]) {
    LaneVertex4<Sampler> v(scene, path, hit, sampler, shadow, hasShadow);
    const Mask4 alive = shadeVertex(v, settings);
    v.finish();
    return alive.bits();
}

#endif  // CA_FLOAT4_SSE

}  // namespace caustica
