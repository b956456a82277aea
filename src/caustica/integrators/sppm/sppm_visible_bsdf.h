// sppm_visible_bsdf.h — the BSDF of one visible point, resolved once for the many photons that
// visible point gathers. evalBsdf (scene/bsdf.h) walks the BSDF tree, builds the shading frame,
// resolves twosided / bumpmap / normalmap, applies the textures and turns wo into the local frame
// at every call; for one visible point all of that depends only on (si, wo), which are fixed, and
// only wi changes from photon to photon. The gather (sppm_passes.h) evaluated it ~30 times per
// visible point per iteration at 256x256 on cornell-water, half of the gather's time.
#pragma once

#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/scene/bsdf.h"

namespace caustica {

/// evalBsdf(bsdfs, vp.bsdf, vp.si, vp.wo, wi) for a fixed visible point, bit for bit the same
/// value: when the tree has exactly one leaf for vp.wo (a plain BSDF, or one under twosided,
/// bumpmap, normalmap, or a blend/mask with one child of weight > 0), that leaf is prepared once
/// (bsdf_detail::PreparedLeaf: resolved frame, textured parameters, local wo) and each eval()
/// sums its value times the leaf's weight as subtreeEval does (a diffuse leaf in an unperturbed
/// frame: only the operations its value depends on); other trees call evalBsdf.
/// Not copyable (the prepared leaf may point into itself).
class SppmVisibleBsdf {
public:
    CA_HD SppmVisibleBsdf(Span<const Bsdf> bsdfs, const SppmVisiblePoint& vp) : bsdfs_(bsdfs), vp_(vp) {
        using namespace bsdf_detail;
        const LeafOps ops{bsdfs, vp.si};
        uint32_t leaves = 0, leaf = 0;
        bool flip = false;
        forEachLeaf(bsdfs, ops, vp.bsdf, false, vp.wo, [&](uint32_t l, Float w, bool lf) {
            ++leaves;
            leaf = l;
            weight_ = w;
            flip = lf;
        });
        single_ = leaves == 1;
        none_ = leaves == 0;
        if (!single_) return;
        new (&slot_.leaf) PreparedLeaf(bsdfs, leaf, vp.si, vp.wo, flip);
        diffuse_ = slot_.leaf.bsdf().type == BsdfType::Diffuse && !slot_.leaf.resolved().perturbed;
    }
    SppmVisibleBsdf(const SppmVisibleBsdf&) = delete;
    SppmVisibleBsdf& operator=(const SppmVisibleBsdf&) = delete;

    /// f(vp.wo, wi) · |cosθi| (evalBsdf's value): the diffuse case here, every other one in
    /// evalResolved.
    CA_HD Spectrum eval(Vec3f wi) const {
        if (!diffuse_) return evalResolved(wi);
        // A diffuse leaf in an unperturbed frame: sameSide holds, shadowTerminator is 1 (a product
        // that changes no bit) and evalLocal reads only the local z of wi, which is toLocal's third
        // dot product, dot(wi, n); the sum over the one leaf as subtreeEval forms it.
        const bsdf_detail::PreparedLeaf& leaf = slot_.leaf;
        Spectrum sum;
        const Float z = dot(wi, leaf.resolved().frame.n);
        if (leaf.woLocal().z <= 0 || z <= 0) return sum;
        sum += leaf.bsdf().reflectance * (kInvPi * z) * weight_;
        return sum;
    }

private:
    /// eval for every other tree: the prepared leaf (LeafOps::eval's value), or evalBsdf.
    CA_HD Spectrum evalResolved(Vec3f wi) const {
        if (!single_) return none_ ? Spectrum{} : evalBsdf(bsdfs_, vp_.bsdf, vp_.si, vp_.wo, wi);
        Spectrum sum;  // subtreeEval's sum over the one leaf
        sum += slot_.leaf.eval(wi) * weight_;
        return sum;
    }

    Span<const Bsdf> bsdfs_;
    const SppmVisiblePoint& vp_;
    bool single_ = false, none_ = false, diffuse_ = false;
    Float weight_ = 0;
    bsdf_detail::PreparedLeafSlot slot_;  // built only for a single leaf
};

}  // namespace caustica
