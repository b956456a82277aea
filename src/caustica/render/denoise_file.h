// denoise_file.h — `caustica denoise IN -o OUT`: a rendered file denoised into a new file (the
// app parses, this reads, denoises and writes). A single-view image (.exr, .pfm) is denoised with
// its EXR's AOV layers as guides and any guide files given; a multi-view (stereo) EXR, views
// "left" and "right" (io/exr_multiview.h), view by view with that view's own layers, and written
// back as a multi-view EXR with the same views (docs/DENOISING.md).
#pragma once

#include <string>

#include "caustica/render/denoise.h"

namespace caustica {

struct DenoiseFileRequest {
    std::string input, output;
    /// Guide files overriding the input's layers (single-view inputs only); empty: none.
    std::string albedo{}, normal{}, depth{}, variance{};
    bool ignoreLayers = false;  ///< do not use the input EXR's AOV layers
};

/// What denoiseFile did (for the app's summary line).
struct DenoiseFileResult {
    int width = 0, height = 0;  ///< of one view
    int views = 1;              ///< 2 for a stereo pair
    bool albedo = false, normal = false, depth = false, variance = false;  ///< guides used (every view)
};

/// Reads `request.input`, denoises it and writes `request.output`. Throws caustica::Error, with
/// one line naming the file or option, before anything is written when: the output would be the
/// input or cannot be written; the input's views are not exactly left and right; a multi-view
/// input is given guide files (its guides are its views' layers) or an output that is not .exr.
DenoiseFileResult denoiseFile(const DenoiseFileRequest& request, const DenoiseSettings& settings);

}  // namespace caustica
