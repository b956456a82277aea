// pixel_variance.h — per-pixel sample moments of the main image's radiance samples and, from
// them, the variance of each pixel's estimate (the `variance` AOV). For a pixel with n valid
// samples L_1..L_n (per RGB channel) the unbiased sample variance is
//     s² = (Σ L_i² − (Σ L_i)² / n) / (n − 1)
// and the variance of their mean, the pixel estimate, s² / n. The samples are a pixel's own (a
// box filter): for a wider reconstruction filter this estimates the main image's variance, it
// does not follow the filter's weights. Pixels with fewer than 2 samples get 0 (develop's
// `undefined`). Deterministic: one work item per pixel adds its samples in slot order.
// The same moments serve batch means (addEstimate): each sample is then one batch estimate of the
// pixel (one step's image of mlt, sppm or ppm; docs/AOV.md), and s² / n the variance of their mean.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "caustica/film/film.h"
#include "caustica/parallel/device.h"

namespace caustica {

class PixelVariance {
public:
    PixelVariance(int width, int height, Device device = Device::cpu());
    /// Adds a pass's valid samples (film.h's isValidSample and sampleOffset: what the Film keeps).
    void addPass(const SamplePass& pass);
    /// Adds one batch estimate per pixel (an image of the film's size): its finite values count as
    /// one sample of their pixel (per pixel all three channels, or none).
    void addEstimate(const Image& estimate);
    /// s² / n per pixel and RGB channel: values[pixel * 3 + c]; `undefined` where n < 2.
    std::vector<float> develop(float undefined = 0.0f) const;

    void save(std::ostream& out) const;
    /// Refuses (caustica::Error, state unchanged) another size or a damaged stream.
    void load(std::istream& in);

private:
    int width_ = 0, height_ = 0;
    Device device_;
    std::vector<double> moments_;  // per pixel: n, Σr, Σg, Σb, Σr², Σg², Σb²
};

}  // namespace caustica
