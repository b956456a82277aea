// bsdf_delta_lobes.h — every delta (perfectly specular) lobe of a BSDF at a surface point, with
// its full weight, for integrators that follow all of them at once (Whitted ray tracing) instead
// of choosing one by a random number as sampleBsdf does.
//
// A lobe's weight is what sampleBsdf's weight times its discrete probability would be: the
// factor by which radiance arriving along `wi` leaves along `wo`. Per leaf (bsdf.h's sampleLocal):
//   dielectric      reflection F·R, refraction (1 - F)·T·(η_i/η_t)² (radiance mode)
//   thindielectric  reflection R' ·R, straight through (1 - R')·T, R' = 2F / (1 + F)
//   conductor       reflection R·F_conductor(cosθ)
//   plastic         the coating's mirror reflection R_spec·F(cosθ) (its diffuse base is smooth)
// The leaves come from bsdf_composite.h's tree walk with their blend weights and mask
// opacities; what the leaves' weights leave of 1 (null BSDFs, a mask's transparency) passes
// straight through with that weight. The smooth (non-delta) parts are not lobes here: evalBsdf
// gives them.
#pragma once

#include "caustica/scene/bsdf.h"

namespace caustica {

/// One delta lobe: incident direction (world space, unit), weight, and the relative IOR η_t/η_i
/// of the interface it crosses (1 for a reflection or a straight pass).
struct DeltaLobe {
    Vec3f wi;
    Spectrum weight;
    Float eta = 1;
};

/// Most lobes deltaLobes returns: two per leaf, and the straight pass.
constexpr int kMaxDeltaLobes = 2 * kMaxBsdfTreeLeaves + 1;

namespace bsdf_detail {

/// The delta lobes of a non-composite BSDF in its local frame (wo.z > 0: outside); returns how
/// many were written to `out` (at most 2).
CA_HD_INLINE int deltaLobesLocal(const Bsdf& b, Vec3f wo, DeltaLobe* out) {
    int n = 0;
    switch (b.type) {
        case BsdfType::Dielectric: {
            const FresnelDielectric f = fresnelDielectric(wo.z, b.etaRatio);
            if (f.r > 0) out[n++] = {reflectLocal(wo), b.reflectance * f.r, 1};
            if (f.r < 1)
                out[n++] = {refractLocal(wo, f.cosThetaT, f.etaTI),
                            b.transmittance * ((1 - f.r) * sqr(f.etaTI)), f.etaIT};
            return n;
        }
        case BsdfType::ThinDielectric: {
            const Float f = fresnelDielectric(std::fabs(wo.z), b.etaRatio).r;
            const Float r = f * 2 / (1 + f);
            if (r > 0) out[n++] = {reflectLocal(wo), b.reflectance * r, 1};
            if (r < 1) out[n++] = {-wo, b.transmittance * (1 - r), 1};
            return n;
        }
        case BsdfType::Conductor:
            if (wo.z <= 0) return 0;
            out[n++] = {reflectLocal(wo), b.reflectance * fresnelConductor(wo.z, b.eta, b.k), 1};
            return n;
        case BsdfType::Plastic:
            if (wo.z <= 0) return 0;
            out[n++] = {reflectLocal(wo), b.reflectance * fresnelDielectric(wo.z, b.etaRatio).r, 1};
            return n;
        default:
            return 0;  // smooth BSDFs
    }
}

}  // namespace bsdf_detail

/// The delta lobes of BSDF `id` at `si` seen from `wo` (world space, unit, towards the viewer)
/// into `out` (kMaxDeltaLobes entries); returns their number. Lobes of zero weight are dropped.
CA_HD_INLINE int deltaLobes(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                            Vec3f wo, DeltaLobe* out) {
    using namespace bsdf_detail;
    const LeafOps leaf{bsdfs, si};
    int n = 0;
    Float leafWeight = 0;
    forEachLeaf(bsdfs, leaf, id, false, wo, [&](uint32_t l, Float w, bool flip) {
        leafWeight += w;
        const Resolved r = resolve(bsdfs, l, si, wo, flip);
        BsdfScratch scratch;
        const Bsdf& b = applyBsdfTextures(*r.bsdf, si, scratch);
        DeltaLobe local[2];
        const int k = deltaLobesLocal(b, r.frame.toLocal(wo), local);
        for (int i = 0; i < k; ++i) {
            const Vec3f wi = r.frame.toWorld(local[i].wi);
            if (!sameSide(r, wi)) continue;
            const Spectrum weight = local[i].weight * (w * shadowTerminator(r, wi));
            if (!weight.isBlack()) out[n++] = {wi, weight, local[i].eta};
        }
    });
    // Null leaves and masks' transparency: the rest of the unit weight goes straight through.
    // Rounding of blend weights that sum to one leaves a few ulps (1 ulp = 6e-8), no transparency.
    const Float through = 1 - leafWeight;
    if (through > Float(1e-6)) out[n++] = {-wo, Spectrum(through), 1};
    return n;
}

}  // namespace caustica
