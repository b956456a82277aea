// film_gather.h — the deterministic splatting of a pass of samples through the reconstruction
// filter, for any number of channels (the RGB Film, film.h, and the N-channel AovFilm,
// aov_film.h). Two kernels, both one work item per pixel, no atomics:
//
// Kernel 1 (gatherWeights, per source pixel) validates each of its K samples and stores the
// sample's 1-D filter weights towards the 2f+1 output columns and rows it can reach
// (f = footprint, n = 2f + 1):
//   weights[s * 2n + e]     = w(dx) for output column x = sx + e - f
//   weights[s * 2n + n + e] = w(dy) for output row    y = sy + e - f
// (all 0 for an invalid sample), so each exp() of a gaussian is evaluated once per sample and
// axis instead of once per sample and output pixel.
// Kernel 2 (gatherSums, per output pixel) visits source rows y - f .. y + f, columns x - f ..
// x + f (clipped to the image and, on a stereo film, to the pixel's eye), samples k = 0 .. K-1, in that fixed order, and sums w v per channel and w: the same
// additions in the same order whatever the thread count or device.
//
// The box filter (Mitsuba's default, one pixel wide) weighs every valid sample of a pixel 1 and
// reaches no other pixel: kernel 1 then does nothing (no weights are stored) and kernel 2
// validates its own pixel's samples, counts the invalid ones and adds the valid ones with w = 1 —
// the sums the general path forms, bit for bit, without writing and reading back 8 bytes of
// weights per sample.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "caustica/film/eye_seam.h"
#include "caustica/film/filter.h"
#include "caustica/util/math.h"

namespace caustica {

/// How far (pixels) a sample may stray outside its own pixel before it counts as invalid.
inline constexpr Float kSampleSlack = 1.0f / 64.0f;

/// What both kernels see of a pass: plain pointers, valid on the device that runs them.
struct GatherGrid {
    int width = 0, height = 0, samplesPerPixel = 0;
    int footprint = 0;  // f: source pixels visited on each side of the output pixel
    int eyeWidth = 0;   // stereo: one eye's width; the filter never crosses the seam (eye_seam.h)
    bool box = false;   // the box filter: kernel 2 validates and sums alone (see the file comment)
    Filter filter;
    float* weights = nullptr;     // 2 (2f + 1) per sample
    uint32_t* invalid = nullptr;  // per source pixel: its invalid samples
};

/// The grid of a width x height pass of K samples per pixel: `weights` sized for it (host
/// scratch kept across passes), `invalid` one entry per pixel; `eyeWidth` > 0 for a stereo film.
inline GatherGrid gatherGrid(int width, int height, int samplesPerPixel, const Filter& filter,
                             std::vector<float>& weights, std::vector<uint32_t>& invalid,
                             int eyeWidth = 0) {
    GatherGrid g;
    g.eyeWidth = eyeWidth;
    g.width = width;
    g.height = height;
    g.samplesPerPixel = samplesPerPixel;
    g.footprint = filter.footprint();
    g.filter = filter;
    g.box = filter.type == FilterType::Box && g.footprint == 0;
    weights.resize(g.box ? 0
                         : size_t(width) * size_t(height) * size_t(samplesPerPixel) *
                               size_t(2 * (2 * g.footprint + 1)));
    invalid.resize(size_t(width) * size_t(height));
    g.weights = weights.data();
    g.invalid = invalid.data();
    return g;
}

/// Offset of film position `pos` inside pixel (px, py) (in [0, 1) per axis), or false when it
/// is not finite or lies farther than kSampleSlack outside the pixel's square.
CA_HD_INLINE bool sampleOffset(Vec2f pos, int px, int py, Float& u, Float& v) {
    u = pos.x - Float(px);
    v = pos.y - Float(py);
    if (!(u >= -kSampleSlack && u <= 1 + kSampleSlack && v >= -kSampleSlack &&
          v <= 1 + kSampleSlack))
        return false;
    u = clamp(u, Float(0), kOneMinusEpsilon);
    v = clamp(v, Float(0), kOneMinusEpsilon);
    return true;
}

/// Kernel 1 for one source pixel. Samples: `CA_HD bool position(size_t sample, Vec2f& pos) const`,
/// false for a sample whose values are invalid.
template <class Samples>
CA_HD_INLINE void gatherWeights(const GatherGrid& g, const Samples& samples, size_t pixel) {
    if (g.box) return;  // kernel 2 does it all (boxSums)
    const int px = int(pixel % size_t(g.width)), py = int(pixel / size_t(g.width));
    const int f = g.footprint, n = 2 * f + 1;
    uint32_t invalid = 0;
    for (int k = 0; k < g.samplesPerPixel; ++k) {
        const size_t sample = pixel * size_t(g.samplesPerPixel) + size_t(k);
        float* w = g.weights + sample * size_t(2 * n);
        Vec2f pos;
        Float u, v;
        if (!samples.position(sample, pos) || !sampleOffset(pos, px, py, u, v)) {
            ++invalid;
            for (int e = 0; e < 2 * n; ++e) w[e] = 0;
            continue;
        }
        // Offset from the centre of output pixel px + e - f: integer part exact, fraction in
        // [-0.5, 0.5).
        for (int e = 0; e < n; ++e) {
            w[e] = g.filter.eval(Float(f - e) + (u - 0.5f));
            w[n + e] = g.filter.eval(Float(f - e) + (v - 0.5f));
        }
    }
    g.invalid[pixel] = invalid;
}

/// Kernel 2 of the box filter (g.box) for one pixel: its own K samples, each valid one (as
/// gatherWeights validates) with weight 1; writes g.invalid[pixel]. The general path's sums, bit
/// for bit: there every valid sample's weight is exactly 1 · 1 and every invalid one's 0.
template <int C, class Samples>
CA_HD_INLINE void boxSums(const GatherGrid& g, const Samples& samples, size_t pixel, float (&sum)[C],
                          float& wSum) {
    const int x = int(pixel % size_t(g.width)), y = int(pixel / size_t(g.width));
    float acc[C];
    for (int c = 0; c < C; ++c) acc[c] = 0;
    float ws = 0;
    uint32_t invalid = 0;
    for (int k = 0; k < g.samplesPerPixel; ++k) {
        const size_t sample = pixel * size_t(g.samplesPerPixel) + size_t(k);
        Vec2f pos;
        Float u, v;
        if (!samples.position(sample, pos) || !sampleOffset(pos, x, y, u, v)) {
            ++invalid;
            continue;
        }
        const float w = 1;
        float value[C];
        samples.sampleValues(sample, value);
        for (int c = 0; c < C; ++c) acc[c] += w * value[c];
        ws += w;
    }
    g.invalid[pixel] = invalid;  // (each of the AOV film's channel groups writes the same count)
    for (int c = 0; c < C; ++c) sum[c] = acc[c];
    wSum = ws;
}

/// Kernel 2 for one output pixel: sum[c] = Σ w v_c for the C channels (Samples:
/// `CA_HD void sampleValues(size_t sample, float (&v)[C]) const`), wSum = Σ w. One pass adds at
/// most (2f + 1)^2 K terms: float sums lose nothing that matters (the callers keep long-running
/// totals in double).
template <int C, class Samples>
CA_HD_INLINE void gatherSums(const GatherGrid& g, const Samples& samples, size_t pixel,
                             float (&sum)[C], float& wSum) {
    if (g.box) {
        boxSums<C>(g, samples, pixel, sum, wSum);
        return;
    }
    const int x = int(pixel % size_t(g.width)), y = int(pixel / size_t(g.width));
    const int K = g.samplesPerPixel, f = g.footprint, n = 2 * f + 1;
    // Local sums (registers): the output may alias the float weights as far as the compiler knows.
    float acc[C];
    for (int c = 0; c < C; ++c) acc[c] = 0;
    float ws = 0;
    int xLo, xHi;
    eyeColumnRange(x, f, g.width, g.eyeWidth, xLo, xHi);
    for (int sy = max(0, y - f); sy <= min(g.height - 1, y + f); ++sy) {
        const int ey = n + (y - sy + f);
        for (int sx = xLo; sx <= xHi; ++sx) {
            const int ex = x - sx + f;
            const size_t base = (size_t(sy) * size_t(g.width) + size_t(sx)) * size_t(K);
            for (int k = 0; k < K; ++k) {
                const float* w1 = g.weights + (base + size_t(k)) * size_t(2 * n);
                const float w = w1[ex] * w1[ey];
                // Skip, not multiply: an invalid sample has weight 0 but may carry NaN (adding
                // the +0 a zero weight gives would change no sum).
                if (w != 0) {
                    float v[C];
                    samples.sampleValues(base + size_t(k), v);
                    for (int c = 0; c < C; ++c) acc[c] += w * v[c];
                }
                ws += w;
            }
        }
    }
    for (int c = 0; c < C; ++c) sum[c] = acc[c];
    wSum = ws;
}

}  // namespace caustica
