// pixel_variance.cpp — sample moments per pixel and the variance of the pixel mean.
#include "caustica/film/pixel_variance.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>

#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {
constexpr int kMoments = 7;
// Little-endian: char[8] "CAVARI\r\n" | u32 version | i32 width, height | f64[7 * pixels] | u64
// hash.
constexpr char kMagic[8] = {'C', 'A', 'V', 'A', 'R', 'I', '\r', '\n'};
constexpr uint32_t kVersion = 1;
}  // namespace

PixelVariance::PixelVariance(int width, int height, Device device)
    : width_(width), height_(height), device_(device) {
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxImagePixels)
        throw Error("variance film size is not positive or too large");
    moments_.assign(size_t(width) * size_t(height) * kMoments, 0.0);
}

void PixelVariance::addPass(const SamplePass& pass) {
    if (pass.width != width_ || pass.height != height_)
        throw Error("sample pass does not match the variance film");
    const PixelSample* samples = pass.samples.data();
    double* moments = moments_.data();
    const int K = pass.samplesPerPixel, width = width_;
    parallelFor(device_, "pixel_variance", size_t(width_) * size_t(height_), [=](size_t pixel) {
        const int px = int(pixel % size_t(width)), py = int(pixel / size_t(width));
        double* m = moments + pixel * kMoments;
        for (int k = 0; k < K; ++k) {
            const PixelSample& s = samples[pixel * size_t(K) + size_t(k)];
            Float u, v;
            if (!isValidSample(s) || !sampleOffset(s.pos, px, py, u, v)) continue;
            m[0] += 1;
            for (int c = 0; c < 3; ++c) {
                m[1 + c] += double(s.L[c]);
                m[4 + c] += double(s.L[c]) * double(s.L[c]);
            }
        }
    });
}

void PixelVariance::addEstimate(const Image& estimate) {
    if (estimate.width != width_ || estimate.height != height_)
        throw Error("batch estimate does not match the variance film");
    const float* rgb = estimate.rgb.data();
    double* moments = moments_.data();
    parallelFor(device_, "pixel_variance_batch", size_t(width_) * size_t(height_), [=](size_t pixel) {
        const float* v = rgb + 3 * pixel;
        if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) return;
        double* m = moments + pixel * kMoments;
        m[0] += 1;
        for (int c = 0; c < 3; ++c) {
            m[1 + c] += double(v[c]);
            m[4 + c] += double(v[c]) * double(v[c]);
        }
    });
}

std::vector<float> PixelVariance::develop(float undefined) const {
    const size_t pixels = size_t(width_) * size_t(height_);
    std::vector<float> out(pixels * 3, 0.0f);
    for (size_t i = 0; i < pixels; ++i) {
        const double* m = &moments_[i * kMoments];
        const double n = m[0];
        if (n < 2) {
            for (int c = 0; c < 3; ++c) out[i * 3 + size_t(c)] = undefined;
            continue;
        }
        for (int c = 0; c < 3; ++c) {
            const double s2 = std::max(0.0, (m[4 + c] - m[1 + c] * m[1 + c] / n) / (n - 1));
            out[i * 3 + size_t(c)] = float(s2 / n);
        }
    }
    return out;
}

void PixelVariance::save(std::ostream& out) const {
    BinaryWriter w(out, "variance checkpoint");
    w.bytes(kMagic, sizeof(kMagic));
    w.u32(kVersion);
    w.u32(uint32_t(width_));
    w.u32(uint32_t(height_));
    for (double v : moments_) w.f64(v);
    const uint64_t hash = w.hash();
    w.u64(hash);
    if (!out) throw Error("variance checkpoint: write failed");
}

void PixelVariance::load(std::istream& in) {
    BinaryReader r(in, "variance checkpoint");
    char magic[8];
    r.bytes(magic, sizeof(magic));
    if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0 || r.u32() != kVersion)
        throw Error("variance checkpoint: missing or of another version");
    if (int(r.u32()) != width_ || int(r.u32()) != height_)
        throw Error("variance checkpoint: size does not match the render's");
    std::vector<double> moments(moments_.size());
    for (double& v : moments) v = r.f64();
    const uint64_t expected = r.hash();
    if (r.u64() != expected) throw Error("variance checkpoint: checksum mismatch (corrupt data)");
    moments_ = std::move(moments);
}

}  // namespace caustica
