// build_textures.h — Mitsuba 3 <texture> plugins -> caustica::Texture records, and how BSDF
// builders read parameters that may be textures (see scene/texture.h for the kernel side).
#pragma once

#include <string>

#include "caustica/io/mitsuba/build_context.h"

namespace caustica::mitsuba {

/// Index into ctx.scene.textures of the <texture> `object` (nested or referenced), built on first
/// use (a referenced texture is one record however many parameters use it).
uint32_t buildTexture(BuildContext& ctx, int object);

/// The <texture> child of `p` (nested or <ref>) whose name attribute is `name`, or -1.
int findTextureChild(const Params& p, const std::string& name);

/// True when parameter `name` is given as a value or as a texture.
bool hasParam(const Params& p, const std::string& name);

/// A colour parameter that may be a texture (Mitsuba's props.texture): a value (<rgb>, <float>,
/// <spectrum>) is returned as is; a texture adds an entry (param, texture) to b.textures and
/// returns the texture's mean (what Mitsuba's precomputations, e.g. plastic's sampling weight,
/// use). A constant texture (rawconstant) is returned as its value.
Spectrum readSpectrumParam(BuildContext& ctx, Params& p, const std::string& name, Spectrum def,
                           Bsdf& b, BsdfParam param);
/// The same for a float parameter (a texture's value is its luminance, Mitsuba's eval_1).
Float readFloatParam(BuildContext& ctx, Params& p, const std::string& name, Float def, Bsdf& b,
                     BsdfParam param);

/// Errors for <texture> children of the bsdf `p` that no parameter read (misspelt names).
void checkTextureChildren(BuildContext& ctx, const Params& p);

/// Mitsuba's bumpmap and normalmap BSDF adapters (registered in build_bsdfs.cpp).
Bsdf buildBumpMap(BuildContext& ctx, Params& p);
Bsdf buildNormalMap(BuildContext& ctx, Params& p);

}  // namespace caustica::mitsuba
