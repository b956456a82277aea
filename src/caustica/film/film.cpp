// film.cpp — pass splatting, development and checkpoints of the deterministic film.
#include "caustica/film/film.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <istream>
#include <numeric>
#include <ostream>
#include <string>

#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

std::string sizeString(int w, int h) {
    return std::to_string(w) + " x " + std::to_string(h);
}

// ---- checkpoint format ------------------------------------------------------------------------
// All fields little-endian:
//   char[8] magic "CAFILM\r\n" | u32 version | i32 width | i32 height | u32 filter type
//   f32 radius | f32 stddev | u64 samplesPerPixel | u64 invalidSamples | u64 pixel count
//   f64[4 * pixels] sums (r, g, b, w per pixel) | u64 FNV-1a hash of every preceding byte
constexpr char kMagic[8] = {'C', 'A', 'F', 'I', 'L', 'M', '\r', '\n'};
constexpr uint32_t kVersion = 1;

}  // namespace

SamplePass::SamplePass(int w, int h, int k) : width(w), height(h), samplesPerPixel(k) {
    if (w < 0 || h < 0 || k < 0 || uint64_t(w) * uint64_t(h) > kMaxImagePixels ||
        uint64_t(w) * uint64_t(h) * uint64_t(k) > (uint64_t(1) << 32))
        throw Error("sample pass " + sizeString(w, h) + " x " + std::to_string(k) +
                    " spp is negative or too large");
    samples.resize(size_t(w) * size_t(h) * size_t(k));
}

Film::Film(int width, int height, const Filter& filter, Device device)
    : filter_(filter), device_(device) {
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxImagePixels)
        throw Error("film size " + sizeString(width, height) + " is not positive or too large");
    width_ = width;
    height_ = height;
    sums_.assign(size_t(width) * size_t(height), FilmPixel{});
    invalidScratch_.assign(sums_.size(), 0);
}

Film::Film(const FilmDesc& desc, Device device)
    : Film(desc.width, desc.height, Filter::fromDesc(desc.filter), device) {
    setEyeWidth(desc.eyeWidth);
}

void Film::setEyeWidth(int eyeWidth) {
    if (eyeWidth != 0 && 2 * eyeWidth != width_)
        throw Error("stereo film: eye width " + std::to_string(eyeWidth) + " is not half the film width " +
                    std::to_string(width_));
    eyeWidth_ = eyeWidth;
}

void Film::checkPass(const SamplePass& pass) const {
    if (pass.width != width_ || pass.height != height_)
        throw Error("sample pass " + sizeString(pass.width, pass.height) + " does not match film " +
                    sizeString(width_, height_));
    if (pass.samplesPerPixel < 0 ||
        pass.samples.size() != sums_.size() * size_t(pass.samplesPerPixel))
        throw Error("sample pass holds " + std::to_string(pass.samples.size()) +
                    " samples, expected " + std::to_string(pass.samplesPerPixel) + " per pixel");
}

std::vector<PassPixelSums> Film::passSums(const SamplePass& pass, uint64_t& invalidSamples) {
    checkPass(pass);
    std::vector<PassPixelSums> out(sums_.size());
    invalidSamples = 0;
    if (pass.samplesPerPixel == 0) return out;
    FilmSplatView view;
    view.grid = gatherGrid(width_, height_, pass.samplesPerPixel, filter_, weightScratch_, invalidScratch_,
                           eyeWidth_);
    view.samples = pass.samples.data();
    // The CPU's kernels (out is host memory), the same gatherSums as gatherPixel's: the same floats.
    parallelFor(Device::cpu(), "film_sample_weights", sums_.size(),
                [view](size_t pixel) { sampleWeights(view, pixel); });
    PassPixelSums* o = out.data();
    parallelFor(Device::cpu(), "film_pass_sums", sums_.size(), [view, o](size_t pixel) {
        float sum[3], wSum;
        gatherSums<3>(view.grid, view, pixel, sum, wSum);
        o[pixel] = PassPixelSums{sum[0], sum[1], sum[2], wSum};
    });
    invalidSamples = std::accumulate(invalidScratch_.begin(), invalidScratch_.end(), uint64_t(0));
    return out;
}

void Film::addPassSums(const std::vector<PassPixelSums>& sums, int samplesPerPixel, uint64_t invalidSamples) {
    if (sums.size() != sums_.size() || samplesPerPixel < 0)
        throw Error("pass sums of " + std::to_string(sums.size()) + " pixels do not match film " +
                    sizeString(width_, height_));
    if (samplesPerPixel == 0) return;
    for (size_t i = 0; i < sums_.size(); ++i) {  // as gatherPixel adds: float to double
        sums_[i].r += sums[i].r;
        sums_[i].g += sums[i].g;
        sums_[i].b += sums[i].b;
        sums_[i].w += sums[i].w;
    }
    invalidSamples_ += invalidSamples;
    samplesPerPixel_ += uint64_t(samplesPerPixel);
}

void Film::addPass(const SamplePass& pass) {
    checkPass(pass);
    if (pass.samplesPerPixel == 0) return;

    FilmSplatView view;
    view.grid = gatherGrid(width_, height_, pass.samplesPerPixel, filter_, weightScratch_, invalidScratch_,
                           eyeWidth_);
    view.samples = pass.samples.data();
    view.sums = sums_.data();
    parallelFor(device_, "film_sample_weights", sums_.size(),
                [view](size_t pixel) { sampleWeights(view, pixel); });
    parallelFor(device_, "film_gather", sums_.size(),
                [view](size_t pixel) { gatherPixel(view, pixel); });

    // Integer sum: its value does not depend on the order.
    invalidSamples_ += std::accumulate(invalidScratch_.begin(), invalidScratch_.end(), uint64_t(0));
    samplesPerPixel_ += uint64_t(pass.samplesPerPixel);
}

Image Film::develop() const {
    Image image(width_, height_);
    float* out = image.rgb.data();
    const FilmPixel* sums = sums_.data();
    parallelFor(device_, "film_develop", sums_.size(), [out, sums](size_t i) {
        const FilmPixel& p = sums[i];
        const double inv = p.w > 0 ? 1.0 / p.w : 0.0;
        out[3 * i + 0] = float(p.r * inv);
        out[3 * i + 1] = float(p.g * inv);
        out[3 * i + 2] = float(p.b * inv);
    });
    return image;
}

void Film::merge(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        throw Error("cannot merge film " + sizeString(other.width_, other.height_) + " into " +
                    sizeString(width_, height_));
    if (other.filter_.type != filter_.type || other.filter_.radius != filter_.radius ||
        other.filter_.stddev != filter_.stddev)
        throw Error("cannot merge films with different reconstruction filters");
    for (size_t i = 0; i < sums_.size(); ++i) {
        sums_[i].r += other.sums_[i].r;
        sums_[i].g += other.sums_[i].g;
        sums_[i].b += other.sums_[i].b;
        sums_[i].w += other.sums_[i].w;
    }
    samplesPerPixel_ += other.samplesPerPixel_;
    invalidSamples_ += other.invalidSamples_;
}

void Film::reset() {
    std::fill(sums_.begin(), sums_.end(), FilmPixel{});
    samplesPerPixel_ = 0;
    invalidSamples_ = 0;
}

void Film::save(std::ostream& out) const {
    BinaryWriter w(out, "film checkpoint");
    w.bytes(kMagic, sizeof(kMagic));
    w.u32(kVersion);
    w.u32(uint32_t(width_));
    w.u32(uint32_t(height_));
    w.u32(uint32_t(filter_.type));
    w.f32(filter_.radius);
    w.f32(filter_.stddev);
    w.u64(samplesPerPixel_);
    w.u64(invalidSamples_);
    w.u64(sums_.size());
    for (const FilmPixel& p : sums_) {
        w.f64(p.r);
        w.f64(p.g);
        w.f64(p.b);
        w.f64(p.w);
    }
    const uint64_t hash = w.hash();
    w.u64(hash);
    if (!out) throw Error("film checkpoint: write failed");
}

void Film::load(std::istream& in) {
    BinaryReader r(in, "film checkpoint");
    char magic[8];
    r.bytes(magic, sizeof(magic));
    if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
        throw Error("film checkpoint: not a caustica film checkpoint (bad magic number)");
    const uint32_t version = r.u32();
    if (version != kVersion)
        throw Error("film checkpoint: unsupported version " + std::to_string(version) +
                    " (this build reads version " + std::to_string(kVersion) + ")");
    const int w = int(r.u32()), h = int(r.u32());
    if (w != width_ || h != height_)
        throw Error("film checkpoint: size " + sizeString(w, h) + " does not match film " +
                    sizeString(width_, height_));
    const uint32_t type = r.u32();
    const float radius = r.f32(), stddev = r.f32();
    if (type != uint32_t(filter_.type) || radius != filter_.radius || stddev != filter_.stddev)
        throw Error("film checkpoint: reconstruction filter does not match the film's");
    const uint64_t spp = r.u64(), invalid = r.u64(), count = r.u64();
    if (count != sums_.size())
        throw Error("film checkpoint: holds " + std::to_string(count) + " pixels, expected " +
                    std::to_string(sums_.size()));
    std::vector<FilmPixel> sums(sums_.size());
    for (FilmPixel& p : sums) {
        p.r = r.f64();
        p.g = r.f64();
        p.b = r.f64();
        p.w = r.f64();
    }
    const uint64_t expected = r.hash();
    if (r.u64() != expected) throw Error("film checkpoint: checksum mismatch (corrupt data)");
    // Everything checked: commit.
    sums_ = std::move(sums);
    samplesPerPixel_ = spp;
    invalidSamples_ = invalid;
}

}  // namespace caustica
