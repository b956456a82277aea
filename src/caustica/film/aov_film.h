// aov_film.h — an N-channel film for arbitrary output variables (aov_layers.h): passes of K
// samples per pixel, each a film position and N values, reconstructed with the scene's filter by
// the same deterministic gather as the RGB Film (film_gather.h), as Mitsuba develops its AOV
// channels with the film's filter: sum(w v) / sum(w) per channel, 0 where sum(w) = 0.
// Bit-identical for any thread count. Checkpoints: save()/load().
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "caustica/film/film_gather.h"
#include "caustica/film/filter.h"
#include "caustica/parallel/device.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// K samples per pixel of `channels` values: slot = pixel * K + k (pixel = y * width + x), film
/// position positions[slot] (inside the pixel's square), values[slot * channels + c].
struct AovSamplePass {
    int width = 0, height = 0, samplesPerPixel = 0, channels = 0;
    std::vector<Vec2f> positions;
    std::vector<float> values;

    AovSamplePass() = default;
    /// Throws caustica::Error on negative or absurd sizes.
    AovSamplePass(int width, int height, int samplesPerPixel, int channels);
    size_t slots() const { return positions.size(); }
};

/// The gather kernels' view of an AOV pass, one group of up to kAovGatherChannels channels.
inline constexpr int kAovGatherChannels = 4;
struct AovSplatView {
    GatherGrid grid;
    const Vec2f* positions = nullptr;
    const float* values = nullptr;
    int channels = 0;      // per sample
    int firstChannel = 0;  // of this group

    CA_HD bool position(size_t i, Vec2f& pos) const {
        pos = positions[i];
        for (int c = 0; c < channels; ++c)
            if (!std::isfinite(values[i * size_t(channels) + size_t(c)])) return false;
        return true;
    }
    CA_HD void sampleValues(size_t i, float (&v)[kAovGatherChannels]) const {
        const float* in = values + i * size_t(channels);
        for (int c = 0; c < kAovGatherChannels; ++c)
            v[c] = firstChannel + c < channels ? in[firstChannel + c] : 0.0f;
    }
};

class AovFilm {
public:
    AovFilm(int width, int height, const Filter& filter, int channels,
            Device device = Device::cpu());

    int width() const { return width_; }
    int height() const { return height_; }
    int channels() const { return channels_; }
    /// Stereo: one eye's width (the filter treats the seam at x = eyeWidth as a border, as the RGB
    /// Film does); 0 mono. Throws caustica::Error unless 0 or half the width.
    void setEyeWidth(int eyeWidth);
    /// Splats one pass (its size and channel count must match; throws caustica::Error).
    /// Samples with a non-finite value or a position outside their pixel are dropped.
    void addPass(const AovSamplePass& pass);
    /// sum(w v) / sum(w) per pixel and channel, values[pixel * channels + c].
    std::vector<float> develop() const;
    uint64_t samplesPerPixel() const { return samplesPerPixel_; }

    /// The sums and counters in a self-checking little-endian format.
    void save(std::ostream& out) const;
    /// Restores save()'s state; refuses (caustica::Error, film unchanged) another size, channel
    /// count or filter, or a truncated or corrupt stream.
    void load(std::istream& in);

private:
    int width_ = 0, height_ = 0, channels_ = 0, eyeWidth_ = 0;
    Filter filter_;
    Device device_;
    std::vector<double> sums_;  // (channels + 1) per pixel: sum(w v_c) ..., sum(w)
    std::vector<float> weightScratch_;
    std::vector<uint32_t> invalidScratch_;
    uint64_t samplesPerPixel_ = 0;
};

}  // namespace caustica
