// stereo_outputs.h — what a stereo render writes (docs/STEREO.md). The rendered image holds both
// eyes side by side (left eye in columns [0, W), right eye in [W, 2W)):
//   NAME.exr   a multi-view OpenEXR with the views "left" and "right" (io/exr_multiview.h), or with
//              `separate` the two files NAME.left.exr and NAME.right.exr;
//   NAME.png / NAME.pfm   the side-by-side image;
//   anaglyph   a red-cyan colour anaglyph PNG: red from the left eye, green and blue from the right.
#pragma once

#include <string>
#include <vector>

#include "caustica/film/aov_layers.h"
#include "caustica/film/image.h"
#include "caustica/io/image_io.h"

namespace caustica {

struct StereoOutputs {
    bool enabled = false;   // the render is a stereo pair
    bool separate = false;  // NAME.left.exr + NAME.right.exr instead of one multi-view EXR
    std::string anaglyph;   // "" = none; else a .png path
};

/// NAME.left.exr (eye 0) or NAME.right.exr (eye 1) for NAME.exr.
std::string stereoEyePath(const std::string& exrPath, int eye);
/// Every file a run writes for `outputs` (in order, the anaglyph last): with stereo and
/// `separate`, each .exr becomes its two eye files.
std::vector<std::string> stereoOutputFiles(const std::vector<std::string>& outputs, const StereoOutputs& stereo);
/// Columns [eye W, (eye + 1) W) of a side-by-side image of width 2W.
Image stereoEyeImage(const Image& sideBySide, int eye);
/// The AOVs of columns [eye W, (eye + 1) W) of side-by-side AOVs of width 2W.
AovImage stereoEyeAovs(const AovImage& sideBySide, int eye);
/// The side-by-side image of two eyes' images (same size): left in [0, W), right in [W, 2W).
Image sideBySideImage(const Image& left, const Image& right);
/// Red-cyan colour anaglyph of a side-by-side image: (left R, right G, right B) per pixel.
Image anaglyphImage(const Image& sideBySide);
/// Refuses (caustica::Error) an anaglyph path that is not a .png, and every file of
/// stereoOutputFiles that cannot be written (checkImageOutputPath).
void checkStereoOutputFiles(const std::vector<std::string>& outputs, const StereoOutputs& stereo);
/// Writes the anaglyph of a side-by-side display image (tone-mapped already where the film is
/// an ldrfilm) as an 8-bit sRGB PNG.
void writeAnaglyphPng(const std::string& path, const Image& sideBySide, const ImageMetadata& meta);
/// Writes the stereo EXR for `path` (multi-view or two files) from the side-by-side image and,
/// when not empty, its side-by-side AOVs: each view's layers in the multi-view file
/// (io/exr_multiview.h), each eye file's as in a mono render's EXR (io/exr_layers.h).
void writeStereoExr(const std::string& path, const Image& sideBySide, const ImageMetadata& meta, bool separate,
                    const AovImage& sideBySideAovs = {});

}  // namespace caustica
