// build_bsdfs_layered.cpp — Mitsuba 3 BSDF plugins made of a coating or of other BSDFs.
//
// | plugin       | parameters (default)                                                        |
// |--------------|-----------------------------------------------------------------------------|
// | roughplastic | distribution (beckmann), alpha (0.1; isotropic only, as Mitsuba),           |
// |              | sample_visible (true), int_ior (polypropylene), ext_ior (air),              |
// |              | diffuse_reflectance (0.5), specular_reflectance (1), nonlinear (false)      |
// | blendbsdf    | weight (required, as Mitsuba 3.9.1; float, rgb (its mean) or texture;       |
// |              | clamped to [0, 1]), two nested/referenced bsdfs (bsdf_0 at 0, bsdf_1 at 1)  |
// | mask         | opacity (0.5; float, rgb (its mean) or texture; clamped to [0, 1]), one     |
// |              | nested bsdf                                                                 |
// Colour parameters of roughplastic may be textures (build_textures.h); its alpha may not (Mitsuba
// 3.9.1 reads it as a float: its tables are precomputed for one roughness).
// | null         | (none)                                                                      |
// | principled   | base_color (0.5; may be a texture), roughness (0.5), metallic, specular     |
// |              | (0.5) or eta, spec_tint, anisotropic, sheen, sheen_tint, clearcoat,         |
// |              | clearcoat_gloss, spec_trans, flatness (0), the three sampling rates (1).    |
// |              | Values must lie in [0, 1]; base_color and every weight but the sampling     |
// |              | rates may be textures (specular and eta are floats in Mitsuba 3.9.1).       |
// Nested trees must fit the kernels' bounds (bsdf_composite.h, kMaxBsdfTreeLeaves/Depth).
#include "caustica/io/mitsuba/build_bsdfs_layered.h"

#include <algorithm>
#include <cmath>

#include "caustica/io/mitsuba/build_textures.h"

#include "caustica/scene/bsdf.h"

namespace caustica::mitsuba {

namespace {

/// Mitsuba's weight/opacity: a float, a colour's mean (what Mitsuba 3.9.1's scalar_rgb returns
/// for a constant <rgb>, checked through its Python bindings) or a texture (evaluated in the
/// kernels, BsdfParam::Weight), clamped to [0, 1]; an <rgb> above 1 is refused, as by Mitsuba.
Float readUnitWeight(BuildContext& ctx, Params& p, const std::string& name, Float def, Bsdf& b) {
    if (findTextureChild(p, name) >= 0)
        return std::clamp(readFloatParam(ctx, p, name, def, b, BsdfParam::Weight), Float(0),
                          Float(1));
    const Property* prop = p.find(name);
    if (!prop) return def;
    if (prop->type == PropertyType::Rgb || prop->type == PropertyType::Spectrum) {
        const Spectrum s = p.getSpectrum(name, Spectrum(def));  // an <rgb> above 1 is refused when parsed
        return std::clamp((s.r + s.g + s.b) / 3, Float(0), Float(1));
    }
    return std::clamp(p.getFloat(name), Float(0), Float(1));
}

bool leafTransmits(const Bsdf& b) {
    return b.type == BsdfType::Dielectric || b.type == BsdfType::RoughDielectric ||
           b.type == BsdfType::ThinDielectric ||
           (b.type == BsdfType::Principled && b.principled.hasSpecTrans);
}

}  // namespace

void checkBsdfTree(BuildContext& ctx, const Params& p, const std::vector<uint32_t>& children) {
    int leaves = 0, depth = 0;
    for (uint32_t c : children) {
        int l = 0, d = 0;
        bsdfTreeFits(Span<const Bsdf>(ctx.scene.bsdfs), c, &l, &d);
        leaves += l;
        depth = std::max(depth, d + 1);
    }
    if (leaves > kMaxBsdfTreeLeaves || depth > kMaxBsdfTreeDepth)
        p.fail("nests too many bsdfs: " + std::to_string(leaves) + " leaves in " +
               std::to_string(depth) + " levels of blendbsdf/mask/twosided (caustica's kernels " +
               "walk at most " + std::to_string(kMaxBsdfTreeLeaves) + " leaves and " +
               std::to_string(kMaxBsdfTreeDepth) + " levels)");
}

Bsdf buildRoughPlastic(BuildContext& ctx, Params& p) {
    Bsdf r;
    readRoughnessParams(ctx, p, r);
    if (r.alphaU != r.alphaV)
        p.fail("anisotropic roughness (alpha_u != alpha_v) is not supported by roughplastic "
               "(as in Mitsuba 3)");
    const Float intIor = readIorParam(p, "int_ior", 1.49f);
    const Float extIor = readIorParam(p, "ext_ior", 1.000277f);
    if (intIor == extIor) p.fail("int_ior and ext_ior must differ (as in Mitsuba 3)");
    Bsdf tex;  // collects the textured parameters; their means set the sampling weight, as Mitsuba
    const Spectrum diffuse =
        readSpectrumParam(ctx, p, "diffuse_reflectance", Spectrum(0.5f), tex, BsdfParam::Diffuse);
    const Spectrum specular = readSpectrumParam(ctx, p, "specular_reflectance", Spectrum(1.0f),
                                                tex, BsdfParam::Reflectance);
    Bsdf b = makeRoughPlastic(r.distribution, r.alphaU, intIor / extIor, diffuse, specular,
                              p.getBool("nonlinear", false));
    if (r.numTextures > 0)
        p.fail("'alpha' must be a float for roughplastic (Mitsuba 3.9.1 refuses a texture too)");
    for (uint32_t i = 0; i < tex.numTextures; ++i) b.textures[i] = tex.textures[i];
    b.numTextures = tex.numTextures;
    return b;
}

Bsdf buildBlendBsdf(BuildContext& ctx, Params& p) {
    std::vector<int> children = p.takeChildren("bsdf");
    if (children.size() != 2)
        p.fail("needs two nested bsdfs, got " + std::to_string(children.size()));
    if (!hasParam(p, "weight")) p.fail("needs a 'weight' (Mitsuba 3 has no default for it)");
    Bsdf b;
    b.type = BsdfType::Blend;
    b.weight = readUnitWeight(ctx, p, "weight", 0.5f, b);
    b.front = ctx.bsdf(children[0]);
    b.back = ctx.bsdf(children[1]);
    checkBsdfTree(ctx, p, {b.front, b.back});
    return b;
}

Bsdf buildMask(BuildContext& ctx, Params& p) {
    std::vector<int> children = p.takeChildren("bsdf");
    if (children.size() != 1)
        p.fail("needs exactly one nested bsdf, got " + std::to_string(children.size()));
    Bsdf b;
    b.type = BsdfType::Mask;
    b.weight = readUnitWeight(ctx, p, "opacity", 0.5f, b);
    b.front = ctx.bsdf(children[0]);
    checkBsdfTree(ctx, p, {b.front});
    return b;
}

Bsdf buildNull(BuildContext&, Params&) {
    Bsdf b;
    b.type = BsdfType::Null;
    return b;
}

namespace {

/// Mitsuba's get_flag: a principled lobe is active when its parameter is given, unless as the
/// float 0.
bool lobeFlag(const Params& p, const std::string& name) {
    const Property* prop = nullptr;
    for (const Property& q : p.object().properties)
        if (q.name == name) prop = &q;
    if (!prop && findTextureChild(p, name) < 0) return false;
    return !(prop && (prop->type == PropertyType::Float || prop->type == PropertyType::Integer) &&
             prop->number == 0);
}

/// A principled float in [0, 1] (Mitsuba's documented range; other values are refused).
Float unitParam(const Params& p, const std::string& name, Float def) {
    const Float v = p.getFloat(name, def);
    if (v < 0 || v > 1) p.fail(*p.find(name), "must lie in [0, 1]");
    return v;
}

/// A principled weight: a float in [0, 1] or a texture (evaluated with eval_1 in the kernels).
Float weightParam(BuildContext& ctx, Params& p, const std::string& name, Float def, Bsdf& b,
                  BsdfParam param) {
    if (findTextureChild(p, name) >= 0) return readFloatParam(ctx, p, name, def, b, param);
    return unitParam(p, name, def);
}

}  // namespace

Bsdf buildPrincipled(BuildContext& ctx, Params& p) {
    Bsdf b;
    b.type = BsdfType::Principled;
    PrincipledParams& q = b.principled;
    b.reflectance =
        readSpectrumParam(ctx, p, "base_color", Spectrum(0.5f), b, BsdfParam::Reflectance);
    q.hasAnisotropic = lobeFlag(p, "anisotropic");
    q.hasSpecTrans = lobeFlag(p, "spec_trans");
    q.hasSheen = lobeFlag(p, "sheen");
    q.hasSheenTint = lobeFlag(p, "sheen_tint");
    q.hasFlatness = lobeFlag(p, "flatness");
    q.hasSpecTint = lobeFlag(p, "spec_tint");
    q.hasMetallic = lobeFlag(p, "metallic");
    q.hasClearcoat = lobeFlag(p, "clearcoat");
    q.roughness = weightParam(ctx, p, "roughness", 0.5f, b, BsdfParam::Roughness);
    q.anisotropic = weightParam(ctx, p, "anisotropic", 0, b, BsdfParam::Anisotropic);
    q.specTrans = weightParam(ctx, p, "spec_trans", 0, b, BsdfParam::SpecTrans);
    q.sheen = weightParam(ctx, p, "sheen", 0, b, BsdfParam::Sheen);
    q.sheenTint = weightParam(ctx, p, "sheen_tint", 0, b, BsdfParam::SheenTint);
    q.flatness = weightParam(ctx, p, "flatness", 0, b, BsdfParam::Flatness);
    q.specTint = weightParam(ctx, p, "spec_tint", 0, b, BsdfParam::SpecTint);
    q.metallic = weightParam(ctx, p, "metallic", 0, b, BsdfParam::Metallic);
    q.clearcoat = weightParam(ctx, p, "clearcoat", 0, b, BsdfParam::Clearcoat);
    q.clearcoatGloss = weightParam(ctx, p, "clearcoat_gloss", 0, b, BsdfParam::ClearcoatGloss);
    q.specRate = p.getFloat("main_specular_sampling_rate", 1);
    q.clearcoatRate = p.getFloat("clearcoat_sampling_rate", 1);
    q.diffuseRate = p.getFloat("diffuse_reflectance_sampling_rate", 1);
    if (q.specRate < 0 || q.clearcoatRate < 0 || q.diffuseRate < 0)
        p.fail("sampling rates must not be negative");
    if (p.has("eta") && p.has("specular"))
        p.fail("give either 'eta' or 'specular', not both (as in Mitsuba 3)");
    if (p.has("eta")) {
        q.eta = p.getFloat("eta");
        if (!(q.eta > 0)) p.fail(*p.find("eta"), "must be positive");
        if (q.hasSpecTrans && q.eta == 1) q.eta = 1.001f;  // Mitsuba: η = 1 cannot transmit
    } else {
        Float specular = unitParam(p, "specular", 0.5f);
        if (q.hasSpecTrans && specular == 0) specular = 1e-3f;
        q.eta = 2 / (1 - std::sqrt(0.08f * specular)) - 1;
    }
    return b;
}

void checkTwoSidedChild(BuildContext& ctx, Params& p, int childObject, uint32_t child) {
    if (bsdfTreeTransmits(Span<const Bsdf>(ctx.scene.bsdfs), child, leafTransmits))
        p.failAtChild(childObject, "cannot wrap a bsdf that transmits light (" +
                                       ctx.desc.objects[size_t(childObject)].type +
                                       "), as in Mitsuba 3");
}

}  // namespace caustica::mitsuba
