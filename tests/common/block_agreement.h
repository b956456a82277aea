// block_agreement.h — do independent renders agree with a reference within their noise, when
// their error is correlated between neighbouring pixels (MLT: a chain splats neighbouring pixels
// in turn)? Compares 8x8-pixel block means per channel: our variance from R runs (seeds), the
// reference's from its per-pixel variance image; a bound on the mean z^2 and the z-score of the
// image mean. Used by the CPU and GPU MLT tests.
#pragma once

#include <cmath>
#include <vector>

#include "caustica/film/image.h"

namespace caustica::test {

inline constexpr int kBlock = 8;

/// Per block and channel: mean over the block, and the variance of that mean.
struct BlockStats {
    std::vector<double> mean, var;
    double imageMean = 0, imageMeanVar = 0;
};

/// 2x2 box downsampling: a pixel of the half-size image is the mean of its four (the bundled
/// scenes' box filter makes a pixel the plain average over its area); with `variance`, the
/// variances of the means (sum / 16).
inline Image halveImage(const Image& in, bool variance) {
    Image out(in.width / 2, in.height / 2);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double s = 0;
                for (int dy = 0; dy < 2; ++dy)
                    for (int dx = 0; dx < 2; ++dx) s += in.pixel(2 * x + dx, 2 * y + dy)[c];
                out.pixel(x, y)[c] = float(variance ? s / 16 : s / 4);
            }
    return out;
}

/// Block means of R independent images: their average and the variance of that average.
inline BlockStats blocksOfRuns(const std::vector<Image>& runs) {
    const int w = runs[0].width, h = runs[0].height, bw = w / kBlock, bh = h / kBlock;
    const double R = double(runs.size());
    BlockStats s;
    s.mean.assign(size_t(bw * bh * 3), 0);
    s.var.assign(s.mean.size(), 0);
    std::vector<std::vector<double>> perRun(runs.size(), std::vector<double>(s.mean.size(), 0));
    std::vector<double> runMeans(runs.size(), 0);
    for (size_t r = 0; r < runs.size(); ++r) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c) {
                    const double v = runs[r].pixel(x, y)[c];
                    perRun[r][size_t(((y / kBlock) * bw + x / kBlock) * 3 + c)] += v / (kBlock * kBlock);
                    runMeans[r] += v / (double(w) * h * 3);
                }
    }
    for (size_t i = 0; i < s.mean.size(); ++i) {
        double m = 0, m2 = 0;
        for (const auto& b : perRun) m += b[i] / R;
        for (const auto& b : perRun) m2 += (b[i] - m) * (b[i] - m);
        s.mean[i] = m;
        s.var[i] = m2 / (R - 1) / R;
    }
    double m = 0, m2 = 0;
    for (double v : runMeans) m += v / R;
    for (double v : runMeans) m2 += (v - m) * (v - m);
    s.imageMean = m;
    s.imageMeanVar = m2 / (R - 1) / R;
    return s;
}

/// Block means of a reference image with independent per-pixel variances of its mean.
inline BlockStats blocksOfReference(const Image& mean, const Image& var) {
    const int w = mean.width, h = mean.height, bw = w / kBlock;
    BlockStats s;
    s.mean.assign(size_t(bw * (h / kBlock) * 3), 0);
    s.var.assign(s.mean.size(), 0);
    const double n = double(kBlock * kBlock), N = double(w) * h * 3;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const size_t i = size_t(((y / kBlock) * bw + x / kBlock) * 3 + c);
                s.mean[i] += mean.pixel(x, y)[c] / n;
                s.var[i] += var.pixel(x, y)[c] / (n * n);
                s.imageMean += mean.pixel(x, y)[c] / N;
                s.imageMeanVar += var.pixel(x, y)[c] / (N * N);
            }
    return s;
}

struct Agreement {
    double meanZ2 = 0, imageZ = 0, relBias = 0;
    bool passed(int runs) const {
        const double expected = double(runs - 1) / double(runs - 3);  // E[t^2], R - 1 dof
        return meanZ2 < 3.0 * expected && std::fabs(imageZ) < 4.0;
    }
};

inline Agreement compare(const BlockStats& ours, const BlockStats& ref, double scale = 1.0) {
    Agreement a;
    for (size_t i = 0; i < ours.mean.size(); ++i) {
        const double z = (ours.mean[i] * scale - ref.mean[i]) / std::sqrt(ours.var[i] * scale * scale + ref.var[i] + 1e-30);
        a.meanZ2 += z * z / double(ours.mean.size());
    }
    a.imageZ = (ours.imageMean * scale - ref.imageMean) /
               std::sqrt(ours.imageMeanVar * scale * scale + ref.imageMeanVar);
    a.relBias = ours.imageMean * scale / ref.imageMean - 1;
    return a;
}

}  // namespace caustica::test
