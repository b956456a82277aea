// aov_layers.h — arbitrary output variables (AOVs): Mitsuba 3's `aovs` string ("dd.y:depth,
// nn:sh_normal": comma-separated NAME:TYPE pairs, src/integrators/aov.cpp), the channels each type
// writes (Mitsuba's names: depth -> NAME.T, position -> NAME.X/Y/Z, uv -> NAME.U/V, ...), and a
// developed AOV image (N channels per pixel) as the outputs write and the tools read it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace caustica {

/// The AOV types: Mitsuba's (albedo ... shape_index) and caustica's `variance`.
enum class AovType : uint32_t {
    Depth,       // distance along the camera ray to the first hit (Mitsuba's si.t); 0 on a miss
    Position,    // world-space hit point
    Uv,          // surface uv
    GeoNormal,   // geometric normal (outward, flip_normals applied; not turned towards the camera)
    ShNormal,    // shading normal
    Albedo,      // diffuse reflectance of the material (Mitsuba's eval_diffuse_reflectance)
    PrimIndex,   // primitive index inside its shape (triangle of the mesh; 0 for a sphere)
    ShapeIndex,  // 1 + the shape's index in the scene (0: no hit)
    Variance,    // per-pixel variance of the main image's pixel estimate, per RGB channel
};
inline constexpr int kAovTypeCount = 9;

/// Channels a type writes (depth 1, uv 2, position 3, ...).
int aovChannelCount(AovType type);
/// The type's name in an aovs string ("sh_normal").
const char* aovTypeName(AovType type);
/// The channel suffixes, Mitsuba's ("T"; "X", "Y", "Z"; "U", "V"; "R", "G", "B"; "I").
std::vector<std::string> aovChannelSuffixes(AovType type);

struct AovLayer {
    std::string name;  // "dd.y"
    AovType type = AovType::Depth;
};

/// A parsed aovs string. Empty: no AOVs.
struct AovSpec {
    std::vector<AovLayer> layers;
    bool empty() const { return layers.empty(); }
    /// Back to Mitsuba's form, "dd.y:depth,nn:sh_normal" ("" when empty).
    std::string text() const;
    /// The channels of every layer in order: "dd.y.T", "nn.X", "nn.Y", "nn.Z".
    std::vector<std::string> channelNames() const;
    bool has(AovType type) const;
};

/// At most this many layers (the AOV kernel keeps the list in a fixed array).
inline constexpr int kMaxAovLayers = 16;

/// Parses "NAME:TYPE[,NAME:TYPE...]" (spaces around items ignored). Throws caustica::Error
/// "WHERE: REASON" (where = "scene.xml:12" or "--aov") for an empty list, an item that is not a
/// NAME:TYPE pair, an unknown type, a repeated name, a name that would clash with the main
/// image's R, G, B channels, or more than kMaxAovLayers layers.
AovSpec parseAovSpec(const std::string& text, const std::string& where);

/// A developed AOV image: `channels` values per pixel, pixel-major (row-major pixels), named by
/// spec.channelNames().
struct AovImage {
    int width = 0, height = 0;
    AovSpec spec;
    std::vector<std::string> channels;
    std::vector<float> values;  // values[pixel * channels.size() + c]

    bool empty() const { return channels.empty(); }
    float at(int x, int y, size_t c) const {
        return values[(size_t(y) * size_t(width) + size_t(x)) * channels.size() + c];
    }
    /// Index of the first channel of the first layer of `type`, or -1.
    int firstChannelOf(AovType type) const;
};

}  // namespace caustica
