// film.h — deterministic film accumulation by gathering.
//
// The renderer produces samples in passes of K samples per pixel (SamplePass). Film::addPass
// reconstructs each pass with the filter by GATHERING: every output pixel (one work item) visits
// the source pixels in its filter footprint in a fixed order, sums w L and w over the pass and
// adds them to its own double-precision totals. No atomics, no races, the same additions in the
// same order whatever the thread count or device: the image is bit-identical for 1 or N threads.
// Sample positions are never re-binned: a sample stored for pixel p must lie in pixel p.
// develop() divides, like Mitsuba's ImageBlock: sum(w L) / sum(w), 0 where sum(w) = 0.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "caustica/film/eye_seam.h"
#include "caustica/film/filter.h"
#include "caustica/film/image.h"
#include "caustica/parallel/device.h"
#include "caustica/scene/scene.h"
#include "caustica/util/span.h"
#include "caustica/util/spectrum.h"

namespace caustica {

/// One radiance sample: a continuous film position in pixels ((0,0) is the top-left corner of the
/// image, pixel (x, y) covers [x, x+1) x [y, y+1)) and the radiance L carried there.
struct PixelSample {
    Vec2f pos;
    Spectrum L;
};

/// K samples per pixel, stored samples[pixel * K + k] with pixel = y * width + x: a flat array
/// that a CPU or GPU kernel fills by index (the GPU can fill a device copy of the same layout).
/// The sample in slot (pixel, k) must lie inside that pixel's square; positions up to
/// kSampleSlack pixels outside it (rounding) are clamped in, farther ones are invalid.
struct SamplePass {
    int width = 0, height = 0, samplesPerPixel = 0;
    std::vector<PixelSample> samples;

    SamplePass() = default;
    /// Allocates width * height * samplesPerPixel zero samples; throws caustica::Error on
    /// negative or absurd sizes.
    SamplePass(int width, int height, int samplesPerPixel);

    size_t slot(int x, int y, int k) const {
        return (size_t(y) * size_t(width) + size_t(x)) * size_t(samplesPerPixel) + size_t(k);
    }
    PixelSample& at(int x, int y, int k) { return samples[slot(x, y, k)]; }
    const PixelSample& at(int x, int y, int k) const { return samples[slot(x, y, k)]; }
    Span<PixelSample> span() { return Span<PixelSample>(samples.data(), samples.size()); }
    Span<const PixelSample> span() const {
        return Span<const PixelSample>(samples.data(), samples.size());
    }
};

/// How far (pixels) a sample may stray outside its own pixel before it counts as invalid.
inline constexpr Float kSampleSlack = 1.0f / 64.0f;

/// Accumulated sums of one output pixel: sum(w L) per channel and sum(w).
struct FilmPixel {
    double r = 0, g = 0, b = 0, w = 0;
};

/// What the two splatting kernels see: plain pointers, valid on the device that runs them.
///
/// Kernel 1 (sampleWeights, one work item per source pixel) validates each sample and stores
/// its 1-D filter weights towards the 2f+1 output columns and rows it can reach (f = footprint):
///   weights[s * 2n + e]     = w(dx) for output column x = sx + e - f   (n = 2f + 1)
///   weights[s * 2n + n + e] = w(dy) for output row    y = sy + e - f
/// (all 0 for an invalid sample). Each exp() of the gaussian is thus evaluated once per sample
/// and axis instead of once per sample and output pixel.
/// Kernel 2 (gatherPixel, one work item per output pixel) multiplies and accumulates.
struct FilmSplatView {
    int width = 0, height = 0, samplesPerPixel = 0;
    int footprint = 0;  // f: source pixels visited on each side of the output pixel
    int eyeWidth = 0;   // stereo: one eye's width; the filter never crosses the seam (eye_seam.h)
    Filter filter;
    const PixelSample* samples = nullptr;
    float* weights = nullptr;     // 2 (2f + 1) per sample
    FilmPixel* sums = nullptr;    // per output pixel
    uint32_t* invalid = nullptr;  // per source pixel: its invalid samples
};

/// True when a sample may be splatted: finite, non-negative radiance and a finite position.
CA_HD_INLINE bool isValidSample(const PixelSample& s) {
    return s.L.isValid() && std::isfinite(s.pos.x) && std::isfinite(s.pos.y);
}

/// Offset of a sample inside its pixel (in [0, 1) per axis), or false when it lies farther than
/// kSampleSlack outside the pixel's square.
CA_HD_INLINE bool sampleOffset(const PixelSample& s, int px, int py, Float& u, Float& v) {
    u = s.pos.x - Float(px);
    v = s.pos.y - Float(py);
    if (!(u >= -kSampleSlack && u <= 1 + kSampleSlack && v >= -kSampleSlack &&
          v <= 1 + kSampleSlack))
        return false;
    u = clamp(u, Float(0), kOneMinusEpsilon);
    v = clamp(v, Float(0), kOneMinusEpsilon);
    return true;
}

/// Kernel 1 for one source pixel: validates its K samples and stores their 1-D weights.
CA_HD_INLINE void sampleWeights(const FilmSplatView& view, size_t pixel) {
    const int px = int(pixel % size_t(view.width)), py = int(pixel / size_t(view.width));
    const int f = view.footprint, n = 2 * f + 1;
    uint32_t invalid = 0;
    for (int k = 0; k < view.samplesPerPixel; ++k) {
        const size_t sample = pixel * size_t(view.samplesPerPixel) + size_t(k);
        float* w = view.weights + sample * size_t(2 * n);
        Float u, v;
        if (!isValidSample(view.samples[sample]) ||
            !sampleOffset(view.samples[sample], px, py, u, v)) {
            ++invalid;
            for (int e = 0; e < 2 * n; ++e) w[e] = 0;
            continue;
        }
        // Offset from the centre of output pixel px + e - f: integer part exact, fraction in
        // [-0.5, 0.5).
        for (int e = 0; e < n; ++e) {
            w[e] = view.filter.eval(Float(f - e) + (u - 0.5f));
            w[n + e] = view.filter.eval(Float(f - e) + (v - 0.5f));
        }
    }
    view.invalid[pixel] = invalid;
}

/// Kernel 2 for one output pixel: visits source rows y - f .. y + f, columns x - f .. x + f,
/// samples k = 0 .. K-1, in that fixed order, and adds sum(w L) and sum(w) to its sums.
CA_HD_INLINE void gatherPixel(const FilmSplatView& view, size_t pixel) {
    const int x = int(pixel % size_t(view.width)), y = int(pixel / size_t(view.width));
    const int K = view.samplesPerPixel, f = view.footprint, n = 2 * f + 1;
    // One pass adds at most (2f + 1)^2 K terms: float sums lose nothing that matters, and the
    // long-running per-pixel totals stay double.
    float r = 0, g = 0, b = 0, wSum = 0;
    int xLo, xHi;
    eyeColumnRange(x, f, view.width, view.eyeWidth, xLo, xHi);
    for (int sy = max(0, y - f); sy <= min(view.height - 1, y + f); ++sy) {
        const int ey = n + (y - sy + f);
        for (int sx = xLo; sx <= xHi; ++sx) {
            const int ex = x - sx + f;
            const size_t base = (size_t(sy) * size_t(view.width) + size_t(sx)) * size_t(K);
            for (int k = 0; k < K; ++k) {
                const float* w1 = view.weights + (base + size_t(k)) * size_t(2 * n);
                const float w = w1[ex] * w1[ey];
                const Spectrum& L = view.samples[base + size_t(k)].L;
                // Select, not multiply: an invalid sample has weight 0 but may carry NaN.
                r += w != 0 ? w * L.r : 0.0f;
                g += w != 0 ? w * L.g : 0.0f;
                b += w != 0 ? w * L.b : 0.0f;
                wSum += w;
            }
        }
    }
    FilmPixel& acc = view.sums[pixel];
    acc.r += r;
    acc.g += g;
    acc.b += b;
    acc.w += wSum;
}

/// Film of width x height pixels accumulating filtered sample passes (see the file comment).
/// Checkpoints: save() / load() write and read the sums in a versioned little-endian format.
class Film {
public:
    Film(int width, int height, const Filter& filter, Device device = Device::cpu());
    explicit Film(const FilmDesc& desc, Device device = Device::cpu());

    int width() const { return width_; }
    int height() const { return height_; }
    const Filter& filter() const { return filter_; }
    /// Stereo: one eye's width (the filter treats the seam at x = eyeWidth as a border); 0 mono.
    int eyeWidth() const { return eyeWidth_; }
    void setEyeWidth(int eyeWidth);

    /// Splats one pass (must match the film's size; throws caustica::Error otherwise). Invalid
    /// samples (NaN, Inf, a negative channel, a position outside their pixel) are counted and
    /// dropped.
    void addPass(const SamplePass& pass);
    /// sum(w L) / sum(w) per pixel, 0 where no sample reached.
    Image develop() const;
    /// Adds another film's sums and counters (e.g. another MPI rank's share); the size and
    /// filter must match.
    void merge(const Film& other);
    /// Forgets everything accumulated.
    void reset();

    /// Samples per pixel accumulated so far (sum of the passes' K, including invalid ones).
    uint64_t samplesPerPixel() const { return samplesPerPixel_; }
    /// Samples dropped because they were invalid.
    uint64_t invalidSamples() const { return invalidSamples_; }
    /// The raw sums, one per pixel, row-major.
    const std::vector<FilmPixel>& sums() const { return sums_; }

    /// Writes the accumulated state (sums and counters) as a checkpoint.
    void save(std::ostream& out) const;
    /// Restores a checkpoint written by save(). Refuses (caustica::Error, film unchanged) a
    /// stream that is not a checkpoint, has another version, size or filter, or is truncated or
    /// corrupt.
    void load(std::istream& in);

private:
    int width_ = 0, height_ = 0;
    int eyeWidth_ = 0;
    Filter filter_;
    Device device_;
    std::vector<FilmPixel> sums_;
    std::vector<float> weightScratch_;  // kernel 1 -> kernel 2, reused across passes
    std::vector<uint32_t> invalidScratch_;
    uint64_t samplesPerPixel_ = 0;
    uint64_t invalidSamples_ = 0;
};

}  // namespace caustica
