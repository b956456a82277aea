// exr_feature_layers.h — denoiser guides read from the AOV layers of a render's EXR.
//
// A caustica EXR with AOVs names them in the string attribute `caustica.aovs`, Mitsuba 3's aov
// syntax "NAME:TYPE,..." (e.g. "albedo:albedo,nn:sh_normal,dd.y:depth,var:variance"), with
// Mitsuba's channel names (src/integrators/aov.cpp): albedo NAME.R/G/B, normals NAME.X/Y/Z,
// depth NAME.T; caustica's variance NAME.R/G/B. Guides are chosen by type: albedo; sh_normal
// (else geo_normal); depth; variance.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "caustica/film/denoise_features.h"

namespace caustica {

/// The EXR attribute that lists a file's AOV layers.
inline constexpr const char* kAovsAttribute = "caustica.aovs";

/// Parses "NAME:TYPE,NAME:TYPE" into (name, type) pairs; throws caustica::Error on an entry
/// without exactly one ':' or with an empty part.
std::vector<std::pair<std::string, std::string>> parseAovSpec(const std::string& spec);

/// The guides held in `path`'s AOV layers (none when the file has no `caustica.aovs`
/// attribute). Throws caustica::Error when the file cannot be read or a listed layer lacks a
/// channel its type needs.
DenoiseFeatures readFeatureLayers(const std::string& path);

}  // namespace caustica
