// build_bsdfs_layered.h — the builders of build_bsdfs_layered.cpp (roughplastic, blendbsdf, mask,
// null, principled) and the parameter readers of build_bsdfs.cpp they share.
#pragma once

#include <string>
#include <vector>

#include "caustica/io/mitsuba/build_context.h"

namespace caustica::mitsuba {

// build_bsdfs.cpp
/// An index of refraction given as a float or as one of Mitsuba's material names.
Float readIorParam(const Params& p, const std::string& name, Float def);
/// distribution, alpha or alpha_u + alpha_v, sample_visible (Mitsuba's MicrofacetDistribution).
void readRoughnessParams(BuildContext& ctx, Params& p, Bsdf& b);

// build_bsdfs_layered.cpp
Bsdf buildRoughPlastic(BuildContext& ctx, Params& p);
Bsdf buildBlendBsdf(BuildContext& ctx, Params& p);
Bsdf buildMask(BuildContext& ctx, Params& p);
Bsdf buildNull(BuildContext& ctx, Params& p);
Bsdf buildPrincipled(BuildContext& ctx, Params& p);
/// Refuses a twosided child that transmits light (Mitsuba: "Only materials without a
/// transmission component can be nested"): dielectrics, mask, null, a blend of such.
void checkTwoSidedChild(BuildContext& ctx, Params& p, int childObject, uint32_t child);
/// Refuses a composite over `children` whose tree the kernels cannot walk (bsdf_composite.h).
void checkBsdfTree(BuildContext& ctx, const Params& p, const std::vector<uint32_t>& children);

}  // namespace caustica::mitsuba
