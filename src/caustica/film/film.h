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

#include "caustica/film/film_gather.h"
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

/// Accumulated sums of one output pixel: sum(w L) per channel and sum(w).
struct FilmPixel {
    double r = 0, g = 0, b = 0, w = 0;
};

/// True when a sample may be splatted: finite, non-negative radiance and a finite position.
CA_HD_INLINE bool isValidSample(const PixelSample& s) {
    return s.L.isValid() && std::isfinite(s.pos.x) && std::isfinite(s.pos.y);
}

/// What the two splatting kernels (film_gather.h) see of an RGB pass.
struct FilmSplatView {
    GatherGrid grid;
    const PixelSample* samples = nullptr;
    FilmPixel* sums = nullptr;  // per output pixel

    CA_HD bool position(size_t i, Vec2f& pos) const {
        pos = samples[i].pos;
        return isValidSample(samples[i]);
    }
    CA_HD void sampleValues(size_t i, float (&v)[3]) const {
        const Spectrum& L = samples[i].L;
        v[0] = L.r;
        v[1] = L.g;
        v[2] = L.b;
    }
};

/// Kernel 1 for one source pixel: validates its K samples and stores their 1-D weights.
CA_HD_INLINE void sampleWeights(const FilmSplatView& view, size_t pixel) { gatherWeights(view.grid, view, pixel); }

/// Kernel 2 for one output pixel: adds sum(w L) and sum(w) of the pass to its sums.
CA_HD_INLINE void gatherPixel(const FilmSplatView& view, size_t pixel) {
    float sum[3], wSum;
    gatherSums<3>(view.grid, view, pixel, sum, wSum);
    FilmPixel& acc = view.sums[pixel];
    acc.r += sum[0];
    acc.g += sum[1];
    acc.b += sum[2];
    acc.w += wSum;
}

/// One pass's filtered sums at an output pixel, sum(w L) and sum(w), in the float precision in
/// which addPass forms them before adding them to the film's doubles.
struct PassPixelSums {
    float r = 0, g = 0, b = 0, w = 0;
};

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
    /// addPass in two halves, for passes rendered elsewhere (other MPI ranks): passSums filters a
    /// pass into per-pixel sums without adding them (and counts its invalid samples);
    /// addPassSums adds them. Adding a pass's sums leaves the same bits as addPass of that pass,
    /// and 16 bytes a pixel travel instead of 20 bytes a sample.
    std::vector<PassPixelSums> passSums(const SamplePass& pass, uint64_t& invalidSamples);
    void addPassSums(const std::vector<PassPixelSums>& sums, int samplesPerPixel, uint64_t invalidSamples);
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
    /// Throws unless `pass` fits the film.
    void checkPass(const SamplePass& pass) const;

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
