// bsdf_composite.h — BSDFs made of other BSDFs, as Mitsuba 3 (3.9.1) evaluates them:
// - twosided (twosided.cpp): `front` where cosθo >= 0, else `back` with both directions mirrored;
// - blendbsdf (blendbsdf.cpp): (1 - weight) · bsdf_0 + weight · bsdf_1 (eval and pdf); sampling
//   picks bsdf_1 when uLobe <= weight (uLobe rescaled), and the returned pdf and weight are
//   those of the whole blend: pdf = w_c pdf_c + w_o pdf_o(wi), weight = (w_c f_c + w_o f_o(wi)) /
//   pdf, where c is the chosen child (its sampled pdf and value, a discrete probability for a
//   delta lobe) and o the other one evaluated at the sampled direction — what Mitsuba 3.9.1's
//   blendbsdf returns (checked against its Python bindings);
// - mask (mask.cpp): opacity · nested (eval and pdf); sampling picks the nested BSDF when
//   uLobe < opacity (rescaled, pdf · opacity, weight unchanged), else passes straight through
//   (a delta "null" sample, pdf 1 - opacity, weight 1);
// - null (null.cpp): passes straight through (delta, pdf 1, weight 1), eval and pdf zero.
// Nested BSDFs reference other entries of the flat array. Device code cannot recurse: eval and
// pdf walk the tree with a fixed stack of kMaxBsdfTreeLeaves entries, sampling walks one branch
// of at most kMaxBsdfTreeDepth levels; the loader refuses trees beyond these bounds
// (bsdfTreeFits). Directions are in world space, `wo` towards the viewer, `wi` towards the
// light; `flip` marks a subtree under the back of a twosided (its shading normal is negated,
// local z mirrored). A `Leaf` object supplies everything else, in world space:
// eval(id, flip, wo, wi), pdf(id, flip, wo, wi), sample(id, flip, wo, uLobe, u, out),
// isDelta(id), the shading normal normal() and the (possibly textured) blend weight / mask
// opacity of a node, weight(b), in [0, 1]. Leaves are the non-composite BSDFs (with
// bumpmap/normalmap chains, which the leaf resolves).
#pragma once

#include "caustica/scene/bsdf_data.h"
#include "caustica/util/span.h"

namespace caustica {

/// Bounds of a BSDF tree the kernels can walk (checked by the loader, bsdfTreeFits).
constexpr int kMaxBsdfTreeLeaves = 8;  // leaves, null included, counted with multiplicity
constexpr int kMaxBsdfTreeDepth = 8;   // composite levels above a leaf

namespace bsdf_detail {

CA_HD_INLINE bool isComposite(BsdfType t) {
    return t == BsdfType::TwoSided || t == BsdfType::Blend || t == BsdfType::Mask ||
           t == BsdfType::Null;
}

/// Whether the entry points of bsdf.h must walk the tree under `id`. Not for a leaf, nor for a
/// twosided over two leaves (Mitsuba's two-sided walls, the commonest composite): resolve()
/// (bsdf.h) takes the child on wo's side and negates the normal under the back, as the walk
/// does, so that child prepared as one leaf gives the walk's bits. A child that is a bumpmap or
/// normalmap counts as a leaf when what it wraps is a plain leaf (resolve() follows at most
/// twosided, then one map, then the leaf).
CA_HD_INLINE bool needsTreeWalk(Span<const Bsdf> bsdfs, uint32_t id) {
    const Bsdf& b = bsdfs[id];
    if (b.type != BsdfType::TwoSided) return isComposite(b.type);
    const auto plainLeaf = [&](uint32_t child) {
        const Bsdf& c = bsdfs[child];
        if (isComposite(c.type)) return false;
        if (c.type != BsdfType::BumpMap && c.type != BsdfType::NormalMap) return true;
        const BsdfType wrapped = bsdfs[c.front].type;
        return !isComposite(wrapped) && wrapped != BsdfType::BumpMap && wrapped != BsdfType::NormalMap;
    };
    return !plainLeaf(b.front) || !plainLeaf(b.back);
}

/// Visits the leaves of the tree under `id` with their weights (products of blend weights and
/// mask opacities) and whether they lie under the back of a twosided: f(id, weight, flip).
/// Null leaves are skipped (no smooth part). With kBothSides, both children of every twosided
/// are visited (for questions that do not depend on the directions).
template <bool kBothSides = false, class Leaf, class F>
CA_HD_INLINE void forEachLeaf(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id, bool flip,
                              Vec3f wo, F&& f) {
    const Float cosO = dot(wo, leaf.normal());
    struct Item {
        uint32_t id;
        Float weight;
        bool flip;
    };
    Item stack[kMaxBsdfTreeLeaves];
    int n = 0;
    stack[n++] = {id, 1, flip};
    while (n > 0) {
        const Item it = stack[--n];
        const Bsdf& b = bsdfs[it.id];
        switch (b.type) {
            case BsdfType::TwoSided: {
                const bool back = (it.flip ? -cosO : cosO) < 0;
                if (kBothSides && b.front != b.back) {
                    if (n + 2 > kMaxBsdfTreeLeaves) return;  // refused by the loader
                    stack[n++] = {b.front, it.weight, it.flip};
                    stack[n++] = {b.back, it.weight, !it.flip};
                    break;
                }
                stack[n++] = {back ? b.back : b.front, it.weight, it.flip != back};
                break;
            }
            case BsdfType::Blend: {
                if (n + 2 > kMaxBsdfTreeLeaves) return;  // refused by the loader
                // kBothSides questions need no weights (nor a surface point to texture them).
                const Float w = kBothSides ? Float(0.5) : leaf.weight(b);
                stack[n++] = {b.front, it.weight * (1 - w), it.flip};
                stack[n++] = {b.back, it.weight * w, it.flip};
                break;
            }
            case BsdfType::Mask:
                stack[n++] = {b.front, kBothSides ? it.weight : it.weight * leaf.weight(b),
                              it.flip};
                break;
            case BsdfType::Null:
                break;
            default:
                if (it.weight > 0) f(it.id, it.weight, it.flip);
        }
    }
}

/// f · |cosθi| of the smooth part of the (sub)tree under `id`.
template <class Leaf>
CA_HD_INLINE Spectrum subtreeEval(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id,
                                  bool flip, Vec3f wo, Vec3f wi) {
    Spectrum sum;
    forEachLeaf(bsdfs, leaf, id, flip, wo, [&](uint32_t l, Float w, bool lf) {
        sum += leaf.eval(l, lf, wo, wi) * w;
    });
    return sum;
}

/// Solid-angle pdf of the smooth samples of the (sub)tree under `id`.
template <class Leaf>
CA_HD_INLINE Float subtreePdf(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id, bool flip,
                              Vec3f wo, Vec3f wi) {
    Float sum = 0;
    forEachLeaf(bsdfs, leaf, id, flip, wo, [&](uint32_t l, Float w, bool lf) {
        sum += leaf.pdf(l, lf, wo, wi) * w;
    });
    return sum;
}

template <class Leaf>
CA_HD_INLINE Spectrum compositeEval(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id,
                                    Vec3f wo, Vec3f wi) {
    return subtreeEval(bsdfs, leaf, id, false, wo, wi);
}

template <class Leaf>
CA_HD_INLINE Float compositePdf(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id, Vec3f wo,
                                Vec3f wi) {
    return subtreePdf(bsdfs, leaf, id, false, wo, wi);
}

/// True when no leaf of the tree has a smooth part (null leaves are delta).
template <class Leaf>
CA_HD_INLINE bool compositeIsDelta(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id) {
    bool delta = true;
    forEachLeaf<true>(bsdfs, leaf, id, false, leaf.normal(),
                      [&](uint32_t l, Float, bool) { delta = delta && leaf.isDelta(l); });
    return delta;
}

/// Samples the tree (see the file comment); out.wi in world space.
template <class Leaf, class Sample>
CA_HD_INLINE bool compositeSample(Span<const Bsdf> bsdfs, const Leaf& leaf, uint32_t id, Vec3f wo,
                                  Float uLobe, Vec2f u, Sample& out) {
    struct Choice {  // a blend or mask on the way down, and the branch taken
        uint32_t id;
        bool flip, second;
    };
    Choice path[kMaxBsdfTreeDepth];
    int depth = 0;
    uint32_t node = id;
    bool flip = false, sampled = false;
    const Float cosO = dot(wo, leaf.normal());
    for (int level = 0; level <= kMaxBsdfTreeDepth && !sampled; ++level) {
        const Bsdf& b = bsdfs[node];
        switch (b.type) {
            case BsdfType::TwoSided: {
                const bool back = (flip ? -cosO : cosO) < 0;
                node = back ? b.back : b.front;
                flip = flip != back;
                break;
            }
            case BsdfType::Blend: {
                if (depth == kMaxBsdfTreeDepth) return false;  // refused by the loader
                const Float w = leaf.weight(b);
                const bool second = w >= 1 || (w > 0 && uLobe <= w);
                uLobe = second ? uLobe / w : (uLobe - w) / (1 - w);
                path[depth++] = {node, flip, second};
                node = second ? b.back : b.front;
                break;
            }
            case BsdfType::Mask: {
                const Float opacity = leaf.weight(b);
                if (uLobe < opacity) {
                    if (depth == kMaxBsdfTreeDepth) return false;
                    uLobe /= opacity;
                    path[depth++] = {node, flip, true};
                    node = b.front;
                    break;
                }
                out.wi = -wo;  // passes straight through
                out.pdf = 1 - opacity;
                out.weight = Spectrum(1.0f);
                out.eta = 1;
                out.delta = true;
                sampled = true;
                break;
            }
            case BsdfType::Null:
                out.wi = -wo;
                out.pdf = 1;
                out.weight = Spectrum(1.0f);
                out.eta = 1;
                out.delta = true;
                sampled = true;
                break;
            default:
                if (!leaf.sample(node, flip, wo, uLobe, u, out)) return false;
                sampled = true;
        }
    }
    if (!sampled || !(out.pdf > 0)) return false;
    // Back up the branch: the masks scale value and pdf, the blends mix in their other child.
    Spectrum value = out.weight * out.pdf;
    Float pdf = out.pdf;
    for (int k = depth - 1; k >= 0; --k) {
        const Bsdf& b = bsdfs[path[k].id];
        const Float w = leaf.weight(b);
        if (b.type == BsdfType::Mask) {
            value = value * w;
            pdf *= w;
            continue;
        }
        const Float wc = path[k].second ? w : 1 - w;
        const uint32_t other = path[k].second ? b.front : b.back;
        value = value * wc + subtreeEval(bsdfs, leaf, other, path[k].flip, wo, out.wi) * (1 - wc);
        pdf = pdf * wc + subtreePdf(bsdfs, leaf, other, path[k].flip, wo, out.wi) * (1 - wc);
    }
    if (!(pdf > 0)) return false;
    out.pdf = pdf;
    out.weight = value * (1 / pdf);
    return true;
}

}  // namespace bsdf_detail

/// Whether the kernels can walk the tree under `id` (kMaxBsdfTreeLeaves, kMaxBsdfTreeDepth).
/// Host only; the children must already be in `bsdfs`.
inline bool bsdfTreeFits(Span<const Bsdf> bsdfs, uint32_t id, int* leaves = nullptr,
                         int* depth = nullptr) {
    int l = 0, d = 0;
    const Bsdf& b = bsdfs[id];
    if (!bsdf_detail::isComposite(b.type) || b.type == BsdfType::Null) {
        l = 1;
    } else {
        int l0 = 0, d0 = 0, l1 = 0, d1 = 0;
        if (!bsdfTreeFits(bsdfs, b.front, &l0, &d0)) return false;
        if (b.type != BsdfType::Mask && !bsdfTreeFits(bsdfs, b.back, &l1, &d1)) return false;
        // A twosided visits one side, or both (compositeIsDelta) when they differ.
        const bool both = b.type == BsdfType::Blend || b.front != b.back;
        l = b.type == BsdfType::Mask ? l0 : l0 + (both ? l1 : 0);
        d = 1 + max(d0, d1);
    }
    if (leaves) *leaves = l;
    if (depth) *depth = d;
    return l <= kMaxBsdfTreeLeaves && d <= kMaxBsdfTreeDepth;
}

/// Whether the tree under `id` can transmit light (Mitsuba's BSDFFlags::Transmission, null
/// included): twosided refuses such children, as Mitsuba. `leafTransmits` judges the leaves.
template <class F>
inline bool bsdfTreeTransmits(Span<const Bsdf> bsdfs, uint32_t id, F&& leafTransmits) {
    const Bsdf& b = bsdfs[id];
    switch (b.type) {
        case BsdfType::Null:
        case BsdfType::Mask:
            return true;
        case BsdfType::TwoSided:
        case BsdfType::Blend:
            return bsdfTreeTransmits(bsdfs, b.front, leafTransmits) ||
                   bsdfTreeTransmits(bsdfs, b.back, leafTransmits);
        default:
            return leafTransmits(b);
    }
}

}  // namespace caustica
