// exr_multiview.h — stereo pairs as one multi-view OpenEXR file (OpenEXR's "Storing Multi-View
// Images in OpenEXR Files", which Nuke and Blender read): the standard attribute `multiView`
// lists the views "left" and "right"; the first, left, is the default view and keeps the
// unprefixed channels R, G, B; the right view's channels are "right.R", "right.G", "right.B".
// float32, ZIP compression, metadata as string attributes (as image_io's single-view EXR).
#pragma once

#include <string>

#include "caustica/film/image.h"
#include "caustica/io/image_io.h"

namespace caustica {

/// Writes `left` and `right` (same size) to `path` as a two-view EXR. Throws caustica::Error
/// naming the file when the sizes differ, a metadata key is reserved, or the write fails.
void writeMultiViewExr(const std::string& path, const Image& left, const Image& right,
                       const ImageMetadata& metadata = {});

/// Reads the views "left" and "right" of a multi-view EXR (the names in its multiView attribute;
/// the default view's channels unprefixed or prefixed). Throws caustica::Error naming the file
/// when it is not a two-view EXR with both views' R, G, B.
struct StereoImagePair {
    Image left, right;
};
StereoImagePair readMultiViewExr(const std::string& path);

}  // namespace caustica
