// exr_feature_layers.h — denoiser guides read from the AOV layers of a render's EXR.
//
// A caustica EXR with AOVs names them in its `caustica.aovs` attribute (io/exr_layers.h, Mitsuba
// 3's aov syntax "NAME:TYPE,...", channels as film/aov_layers.h names them). Guides are chosen by
// type: albedo; sh_normal (else geo_normal); depth; variance — the first layer of each type.
#pragma once

#include <string>

#include "caustica/film/aov_layers.h"
#include "caustica/film/denoise_features.h"

namespace caustica {

/// The guides held in `aovs` (none of a type the list lacks; no variance where it is not finite
/// everywhere).
DenoiseFeatures featuresFromAovs(const AovImage& aovs);

/// The guides held in `path`'s AOV layers (none when the file has no `caustica.aovs`
/// attribute). Throws caustica::Error naming `path` when the file cannot be read or a listed
/// layer lacks one of its channels.
DenoiseFeatures readFeatureLayers(const std::string& path);

}  // namespace caustica
