// aov_film.cpp — splatting, development and checkpoints of the N-channel AOV film.
#include "caustica/film/aov_film.h"

#include <cstring>
#include <istream>
#include <ostream>
#include <string>

#include "caustica/film/image.h"
#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {
// Little-endian: char[8] "CAAOVF\r\n" | u32 version | i32 width, height, channels | u32 filter
// type | f32 radius, stddev | u64 spp | f64[(channels + 1) * pixels] | u64 FNV-1a hash.
constexpr char kMagic[8] = {'C', 'A', 'A', 'O', 'V', 'F', '\r', '\n'};
constexpr uint32_t kVersion = 1;
}  // namespace

AovSamplePass::AovSamplePass(int w, int h, int k, int c)
    : width(w), height(h), samplesPerPixel(k), channels(c) {
    if (w < 0 || h < 0 || k < 0 || c < 0 || uint64_t(w) * uint64_t(h) > kMaxImagePixels ||
        uint64_t(w) * uint64_t(h) * uint64_t(k) * uint64_t(c + 2) > (uint64_t(1) << 32))
        throw Error("aov sample pass " + std::to_string(w) + " x " + std::to_string(h) + " x " +
                    std::to_string(k) + " spp x " + std::to_string(c) +
                    " channels is negative or too large");
    positions.resize(size_t(w) * size_t(h) * size_t(k));
    values.resize(positions.size() * size_t(c));
}

AovFilm::AovFilm(int width, int height, const Filter& filter, int channels, Device device)
    : filter_(filter), device_(device) {
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxImagePixels ||
        channels <= 0 || channels > 256)
        throw Error("aov film " + std::to_string(width) + " x " + std::to_string(height) + " x " +
                    std::to_string(channels) + " channels is not positive or too large");
    width_ = width;
    height_ = height;
    channels_ = channels;
    sums_.assign(size_t(width) * size_t(height) * size_t(channels + 1), 0.0);
    invalidScratch_.assign(size_t(width) * size_t(height), 0);
}

void AovFilm::setEyeWidth(int eyeWidth) {
    if (eyeWidth != 0 && 2 * eyeWidth != width_)
        throw Error("stereo aov film: eye width " + std::to_string(eyeWidth) +
                    " is not half the film width " + std::to_string(width_));
    eyeWidth_ = eyeWidth;
}

void AovFilm::addPass(const AovSamplePass& pass) {
    const size_t pixels = size_t(width_) * size_t(height_);
    if (pass.width != width_ || pass.height != height_ || pass.channels != channels_ ||
        pass.positions.size() != pixels * size_t(pass.samplesPerPixel) ||
        pass.values.size() != pass.positions.size() * size_t(channels_))
        throw Error("aov sample pass does not match the aov film (" + std::to_string(width_) +
                    " x " + std::to_string(height_) + ", " + std::to_string(channels_) +
                    " channels)");
    if (pass.samplesPerPixel == 0) return;
    AovSplatView view;
    view.grid =
        gatherGrid(width_, height_, pass.samplesPerPixel, filter_, weightScratch_, invalidScratch_,
                   eyeWidth_);
    view.positions = pass.positions.data();
    view.values = pass.values.data();
    view.channels = channels_;
    parallelFor(device_, "aov_film_weights", pixels,
                [view](size_t pixel) { gatherWeights(view.grid, view, pixel); });
    double* sums = sums_.data();
    const int C = channels_;
    // One gather per group of kAovGatherChannels channels; the first also adds sum(w).
    for (int first = 0; first < C; first += kAovGatherChannels) {
        AovSplatView group = view;
        group.firstChannel = first;
        parallelFor(device_, "aov_film_gather", pixels, [group, sums, C, first](size_t pixel) {
            float sum[kAovGatherChannels], wSum;
            gatherSums<kAovGatherChannels>(group.grid, group, pixel, sum, wSum);
            double* acc = sums + pixel * size_t(C + 1);
            for (int c = 0; c < kAovGatherChannels && first + c < C; ++c) acc[first + c] += sum[c];
            if (first == 0) acc[C] += wSum;
        });
    }
    samplesPerPixel_ += uint64_t(pass.samplesPerPixel);
}

std::vector<float> AovFilm::develop() const {
    const size_t pixels = size_t(width_) * size_t(height_);
    std::vector<float> out(pixels * size_t(channels_));
    float* o = out.data();
    const double* sums = sums_.data();
    const int C = channels_;
    parallelFor(device_, "aov_film_develop", pixels, [o, sums, C](size_t i) {
        const double* p = sums + i * size_t(C + 1);
        const double inv = p[C] > 0 ? 1.0 / p[C] : 0.0;
        for (int c = 0; c < C; ++c) o[i * size_t(C) + size_t(c)] = float(p[c] * inv);
    });
    return out;
}

void AovFilm::save(std::ostream& out) const {
    BinaryWriter w(out, "aov film checkpoint");
    w.bytes(kMagic, sizeof(kMagic));
    w.u32(kVersion);
    w.u32(uint32_t(width_));
    w.u32(uint32_t(height_));
    w.u32(uint32_t(channels_));
    w.u32(uint32_t(filter_.type));
    w.f32(filter_.radius);
    w.f32(filter_.stddev);
    w.u64(samplesPerPixel_);
    for (double v : sums_) w.f64(v);
    const uint64_t hash = w.hash();
    w.u64(hash);
    if (!out) throw Error("aov film checkpoint: write failed");
}

void AovFilm::load(std::istream& in) {
    BinaryReader r(in, "aov film checkpoint");
    char magic[8];
    r.bytes(magic, sizeof(magic));
    if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
        throw Error("aov film checkpoint: missing (the checkpoint holds no AOVs or is damaged)");
    if (r.u32() != kVersion) throw Error("aov film checkpoint: unsupported version");
    const int w = int(r.u32()), h = int(r.u32()), c = int(r.u32());
    if (w != width_ || h != height_ || c != channels_)
        throw Error("aov film checkpoint: " + std::to_string(w) + " x " + std::to_string(h) +
                    " x " + std::to_string(c) + " channels does not match the render's");
    const uint32_t type = r.u32();
    const float radius = r.f32(), stddev = r.f32();
    if (type != uint32_t(filter_.type) || radius != filter_.radius || stddev != filter_.stddev)
        throw Error("aov film checkpoint: reconstruction filter does not match the film's");
    const uint64_t spp = r.u64();
    std::vector<double> sums(sums_.size());
    for (double& v : sums) v = r.f64();
    const uint64_t expected = r.hash();
    if (r.u64() != expected) throw Error("aov film checkpoint: checksum mismatch (corrupt data)");
    sums_ = std::move(sums);
    samplesPerPixel_ = spp;
}

}  // namespace caustica
