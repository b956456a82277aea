// image_io.h — reading and writing images: OpenEXR, PFM and PNG, chosen by file extension.
//
//   .exr  write: float32 R, G, B, ZIP compression, metadata as string attributes.
//         read:  half, float or uint R,G,B (alpha ignored) or Y-only (grey), data window.
//   .pfm  write: "PF", little-endian, rows bottom to top as the format requires.
//         read:  "PF" (colour) and "Pf" (grey), either byte order, scaled by |scale|.
//   .png  write: 8-bit sRGB (transfer function applied, clamped to [0, 1]), metadata as tEXt.
//         read:  8- or 16-bit grey / RGB (alpha ignored), decoded from sRGB to linear.
//   .jpg, .jpeg  read only: 8-bit grey / RGB, decoded from sRGB to linear.
//   .hdr  read only: Radiance RGBE, linear.
//
// Every failure (missing file, unknown extension, corrupt header, truncated data, absurd size,
// write error) throws caustica::Error naming the file and the reason.
#pragma once

#include <map>
#include <string>

#include "caustica/film/image.h"

namespace caustica {

/// Key/value annotations stored with an image (spp, render time, integrator, seed, ...): EXR
/// string attributes, PNG tEXt chunks; PFM has no room for them (ignored on write).
struct ImageMetadata {
    std::map<std::string, std::string> entries;
};

/// Writes `image` to `path` in the format its extension names (.exr, .pfm, .png, any case). The
/// file is written under a temporary name and renamed into place, so a failed write never
/// leaves a half-written image behind. Metadata keys that clash with the format's own fields
/// (e.g. EXR "compression") are refused.
/// Whether `path` names an OpenEXR file (its extension, in any case, is .exr): the format
/// writeImage and readImage choose for it.
bool isExrPath(const std::string& path);

void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata = {});

/// Reads an image, linear RGB.
Image readImage(const std::string& path);

/// readImage's options: `raw` keeps the stored values of sRGB-encoded formats (PNG, JPEG)
/// instead of decoding them to linear (Mitsuba's bitmap `raw`, for normal and height maps).
struct ImageReadOptions {
    bool raw = false;
};

/// What an image file held: bits per channel (8 or 16 for PNG/JPEG, 32 for float formats; EXR
/// and PFM report 32) and channels (0 when unknown).
struct ImageFileInfo {
    int bitsPerChannel = 32;
    int channels = 0;
};

/// readImage with options; fills `info` when given.
Image readImage(const std::string& path, const ImageReadOptions& options,
                ImageFileInfo* info = nullptr);

/// Refuses (caustica::Error naming `path`) an EXR file that OpenEXR should not be given for
/// reading: a header that claims more than the file holds, an absurd data window, missing or
/// truncated chunks: the checks readImage makes before it reads pixels, for readers of other
/// channels (io/exr_layers.h, io/exr_multiview.h).
void checkExrFile(const std::string& path);

/// Reads an image's metadata: EXR string attributes, PNG tEXt chunks; PFM: always empty.
ImageMetadata readImageMetadata(const std::string& path);

}  // namespace caustica
