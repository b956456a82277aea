// exr_layers.h — one OpenEXR file holding the rendered image and its AOVs as layers:
// float32 channels R, G, B (the image) and every AOV channel under Mitsuba 3's names
// ("dd.y.T", "nn.X", "nn.Y", "nn.Z"; film/aov_layers.h), ZIP compression, the render's metadata as
// string attributes plus "caustica.aovs" = the aovs list ("dd.y:depth,nn:sh_normal"), by which a
// tool (compare, the denoiser) finds the layers of a type. Nuke, Blender and OpenEXR's tools read
// the layers by the dotted channel names.
#pragma once

#include <string>

#include "caustica/film/aov_layers.h"
#include "caustica/film/image.h"
#include "caustica/io/image_io.h"

namespace caustica {

/// The name of the string attribute that holds the aovs list.
inline constexpr const char* kAovsAttribute = "caustica.aovs";

/// Writes `image` and `aovs` (same size) to `path` (any name; the caller renames a temporary
/// file into place). Throws caustica::Error naming `path` (a size mismatch, a metadata key that
/// clashes with EXR's own attributes or with caustica.aovs, a write error).
void writeExrLayers(const std::string& path, const Image& image, const AovImage& aovs,
                    const ImageMetadata& metadata = {});

struct ExrLayers {
    Image image;
    AovImage aovs;  // empty when the file has no caustica.aovs attribute
    ImageMetadata metadata;
};

/// Reads an EXR image (readImage's checks) and, when it has a caustica.aovs attribute, the layers
/// that list names. Throws caustica::Error naming `path` for a malformed list or a missing channel.
ExrLayers readExrLayers(const std::string& path);

}  // namespace caustica
