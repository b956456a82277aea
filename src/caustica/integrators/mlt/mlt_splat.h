// mlt_splat.h — accumulating Metropolis splats into the image, two ways (Frolov & Galaktionov
// 2017, sec. 3.4):
//   atomic  one work item per splat adds its filtered value to every pixel of its footprint with
//           atomic float adds (order, hence rounding, depends on scheduling);
//   sort    splats are sorted by the pixel they fall in (radix sort of the pixel index), each
//           pixel's first splat is found by binary search, and one work item per output pixel
//           gathers the splats of its footprint in sorted order: no atomics, and the image is
//           bit-identical for any thread count.
// Both weight a splat at film position p by the scene's reconstruction filter w(p - centre)
// (filter.h); the driver divides by the filter's integral when it develops the image.
#pragma once

#include <cstdint>

#include "caustica/film/eye_seam.h"
#include "caustica/film/filter.h"
#include "caustica/util/atomic.h"
#include "caustica/util/spectrum.h"

namespace caustica {

/// One splat at film position `pos`, in two layers: `value`, the chain's part (already multiplied
/// by its Metropolis weight; the driver scales this layer by its final estimate of b when it
/// develops the image), and `largeValue`, the large-step proposal's ordinary Monte Carlo part.
struct MltSplat {
    Vec2f pos;
    Spectrum value;
    Spectrum largeValue;
};

/// Values per pixel in the splat sums: chain r, g, b, then large-step r, g, b.
inline constexpr int kMltSplatLayers = 2;
inline constexpr int kMltValuesPerPixel = 3 * kMltSplatLayers;

inline constexpr uint32_t kNoPixel = 0xffffffffu;

/// What the splat kernels see (pointers valid on the device running them).
struct MltSplatView {
    int width = 0, height = 0;
    int eyeWidth = 0;                  // stereo: one eye's width; splats never cross the seam
    Filter filter;
    int footprint = 0;                 // filter.footprint()
    const MltSplat* splats = nullptr;
    uint32_t count = 0;
    float* accum = nullptr;            // atomic: kMltValuesPerPixel floats per pixel, this iteration
    const uint32_t* sortedPixel = nullptr;  // sort: pixel key of each splat, ascending
    const uint32_t* sortedSplat = nullptr;  // sort: splat index, in key order
    const uint32_t* pixelStart = nullptr;   // sort: first sorted entry of pixel p (pixels + 1)
    double* image = nullptr;           // kMltValuesPerPixel doubles per pixel, all iterations
};

/// The pixel a splat falls in, kNoPixel for a zero or invalid splat (those are skipped).
CA_HD_INLINE uint32_t splatPixel(const MltSplatView& v, const MltSplat& s) {
    if (!(s.value.maxValue() > 0 || s.largeValue.maxValue() > 0) || !s.value.isValid() || !s.largeValue.isValid())
        return kNoPixel;
    if (!(s.pos.x >= 0 && s.pos.y >= 0 && s.pos.x < Float(v.width) && s.pos.y < Float(v.height)))
        return kNoPixel;
    const int x = min(int(s.pos.x), v.width - 1), y = min(int(s.pos.y), v.height - 1);
    return uint32_t(y) * uint32_t(v.width) + uint32_t(x);
}

/// Atomic splatting, one work item per splat.
CA_HD_INLINE void splatAtomic(const MltSplatView& v, uint32_t i) {
    const MltSplat s = v.splats[i];
    const uint32_t pixel = splatPixel(v, s);
    if (pixel == kNoPixel) return;
    const int sx = int(pixel % uint32_t(v.width)), sy = int(pixel / uint32_t(v.width));
    int xLo, xHi;
    eyeColumnRange(sx, v.footprint, v.width, v.eyeWidth, xLo, xHi);
    for (int y = max(0, sy - v.footprint); y <= min(v.height - 1, sy + v.footprint); ++y) {
        const Float wy = v.filter.eval(s.pos.y - (Float(y) + 0.5f));
        if (wy == 0) continue;
        for (int x = xLo; x <= xHi; ++x) {
            const Float w = wy * v.filter.eval(s.pos.x - (Float(x) + 0.5f));
            if (w == 0) continue;
            float* a = v.accum + kMltValuesPerPixel * (size_t(y) * size_t(v.width) + size_t(x));
            atomicAddFloat(a + 0, w * s.value.r);
            atomicAddFloat(a + 1, w * s.value.g);
            atomicAddFloat(a + 2, w * s.value.b);
            if (!(s.largeValue.maxValue() > 0)) continue;  // most splats are not large steps
            atomicAddFloat(a + 3, w * s.largeValue.r);
            atomicAddFloat(a + 4, w * s.largeValue.g);
            atomicAddFloat(a + 5, w * s.largeValue.b);
        }
    }
}

/// After atomic splatting, one work item per pixel: moves this iteration's sums into the image.
CA_HD_INLINE void flushAtomicPixel(const MltSplatView& v, uint32_t pixel) {
    for (int c = 0; c < kMltValuesPerPixel; ++c) {
        v.image[kMltValuesPerPixel * size_t(pixel) + c] += double(v.accum[kMltValuesPerPixel * size_t(pixel) + c]);
        v.accum[kMltValuesPerPixel * size_t(pixel) + c] = 0;
    }
}

/// Sort splatting, step 2 (after sorting), one work item per p in [0, pixels]: the first sorted
/// entry whose pixel is >= p (binary search).
CA_HD_INLINE void findPixelStart(uint32_t* pixelStart, const uint32_t* sortedPixel, uint32_t count, uint32_t p) {
    uint32_t lo = 0, hi = count;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (sortedPixel[mid] < p) lo = mid + 1; else hi = mid;
    }
    pixelStart[p] = lo;
}

/// Sort splatting, step 3, one work item per output pixel: gathers the splats of the source
/// pixels in its filter footprint, in sorted order, and adds them to the image.
CA_HD_INLINE void gatherSplats(const MltSplatView& v, uint32_t pixel) {
    const int x = int(pixel % uint32_t(v.width)), y = int(pixel / uint32_t(v.width));
    double sum[kMltValuesPerPixel] = {};
    int xLo, xHi;
    eyeColumnRange(x, v.footprint, v.width, v.eyeWidth, xLo, xHi);
    for (int sy = max(0, y - v.footprint); sy <= min(v.height - 1, y + v.footprint); ++sy) {
        for (int sx = xLo; sx <= xHi; ++sx) {
            const uint32_t source = uint32_t(sy) * uint32_t(v.width) + uint32_t(sx);
            for (uint32_t e = v.pixelStart[source]; e < v.pixelStart[source + 1]; ++e) {
                const MltSplat& s = v.splats[v.sortedSplat[e]];
                const Float w = v.filter.eval(s.pos.x - (Float(x) + 0.5f)) *
                                v.filter.eval(s.pos.y - (Float(y) + 0.5f));
                for (int c = 0; c < 3; ++c) {
                    sum[c] += double(w * s.value[c]);
                    sum[3 + c] += double(w * s.largeValue[c]);
                }
            }
        }
    }
    for (int c = 0; c < kMltValuesPerPixel; ++c) v.image[kMltValuesPerPixel * size_t(pixel) + c] += sum[c];
}

}  // namespace caustica
