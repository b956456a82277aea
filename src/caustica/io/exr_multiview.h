// exr_multiview.h — stereo pairs as one multi-view OpenEXR file (OpenEXR's "Storing Multi-View
// Images in OpenEXR Files", ImfMultiView.h, which Nuke and Blender read): the standard attribute
// `multiView` lists the views "left" and "right"; the first, left, is the default view.
// Channel names follow the convention "layer.view.channel" (multiViewChannelName):
//   the image:      left R, G, B (unprefixed: a single-view reader sees the left eye);
//                   right "right.R", "right.G", "right.B";
//   an AOV channel  "dd.y.T" (film/aov_layers.h) is "dd.y.left.T" and "dd.y.right.T": a layered
//                   channel must name its view even in the default view (OpenEXR puts "dd.y.T"
//                   in no view at all), as Blender writes its passes ("Layer.Pass.left.R").
// With AOVs the file carries the string attribute caustica.aovs (io/exr_layers.h) naming the
// layers. float32, ZIP compression, metadata as string attributes (as image_io's single-view EXR).
#pragma once

#include <string>
#include <vector>

#include "caustica/film/aov_layers.h"
#include "caustica/film/image.h"
#include "caustica/io/image_io.h"

namespace caustica {

/// The name of channel `channel` ("R", "dd.y.T") in view `view` (0: left, the default view;
/// 1: right) under OpenEXR's multi-view convention.
std::string multiViewChannelName(const std::string& channel, int view);

/// Writes `left` and `right` (same size) to `path` as a two-view EXR, with each view's AOV layers
/// when `leftAovs` and `rightAovs` (the same list, the views' size) are not empty. Throws
/// caustica::Error naming the file when the sizes or lists differ, a metadata key is reserved,
/// or the write fails.
void writeMultiViewExr(const std::string& path, const Image& left, const Image& right,
                       const ImageMetadata& metadata = {}, const AovImage& leftAovs = {},
                       const AovImage& rightAovs = {});

/// The views "left" and "right" of a multi-view EXR (the names in its multiView attribute; the
/// default view's image channels unprefixed or prefixed), and each view's AOV layers when the
/// file has a caustica.aovs attribute (empty otherwise). Throws caustica::Error naming the file
/// when it is not a two-view EXR with both views' R, G, B (and every listed AOV channel), or is
/// damaged (image_io's checks before any pixel is read).
/// The view names of `path`'s multiView attribute, in order; empty for a single-view file (no
/// attribute). Throws caustica::Error naming the file when it is not a readable EXR.
std::vector<std::string> exrViews(const std::string& path);

struct StereoImagePair {
    Image left, right;
    AovImage leftAovs, rightAovs;
};
StereoImagePair readMultiViewExr(const std::string& path);

}  // namespace caustica
