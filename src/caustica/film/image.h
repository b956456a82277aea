// image.h — a plain linear-RGB float image (what the film develops, what io/ reads and writes),
// and the sRGB transfer functions that 8-bit outputs need.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "caustica/util/spectrum.h"

namespace caustica {

/// Largest image the loaders accept (width * height), about 16k x 16k: anything beyond is treated
/// as a corrupt header rather than an allocation to attempt.
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

/// Linear RGB image, 3 floats per pixel, row-major, top row first (pixel (x, y) at index
/// 3 * (y * width + x)). Units are whatever the producer stored (radiance for renders).
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;

    Image() = default;
    /// A black image of the given size; throws caustica::Error for negative or absurd sizes.
    Image(int width, int height);

    size_t pixelCount() const { return size_t(width) * size_t(height); }
    bool empty() const { return pixelCount() == 0; }
    bool sameSize(const Image& o) const { return width == o.width && height == o.height; }
    size_t index(int x, int y) const { return 3 * (size_t(y) * size_t(width) + size_t(x)); }

    float* pixel(int x, int y) { return rgb.data() + index(x, y); }
    const float* pixel(int x, int y) const { return rgb.data() + index(x, y); }
    Spectrum at(int x, int y) const {
        const float* p = pixel(x, y);
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, Spectrum s) {
        float* p = pixel(x, y);
        p[0] = s.r, p[1] = s.g, p[2] = s.b;
    }
    /// Sets every pixel to `s`.
    void fill(Spectrum s);
    /// True when every channel of every pixel is finite.
    bool allFinite() const;
};

/// sRGB opto-electronic transfer function (IEC 61966-2-1): linear [0,1] -> encoded [0,1].
CA_HD_INLINE float linearToSrgb(float v) {
    if (!(v > 0.0f)) return 0.0f;  // also maps NaN to 0
    if (v >= 1.0f) return 1.0f;
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

/// Inverse of linearToSrgb: encoded [0,1] -> linear [0,1].
CA_HD_INLINE float srgbToLinear(float v) {
    if (!(v > 0.0f)) return 0.0f;
    if (v >= 1.0f) return 1.0f;
    return v <= 0.04045f ? v * (1.0f / 12.92f) : std::pow((v + 0.055f) * (1.0f / 1.055f), 2.4f);
}

}  // namespace caustica
