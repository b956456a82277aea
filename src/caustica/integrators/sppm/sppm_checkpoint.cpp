#include "caustica/integrators/sppm/sppm_checkpoint.h"

#include <cmath>
#include <string>

#include "caustica/integrators/sppm/sppm_driver.h"
#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {
constexpr uint32_t kMagic = 0x4d505053;  // "SPPM"
constexpr uint32_t kVersion = 2;  // 2: entries per pixel (ppm hitpoints)
constexpr const char* kWhat = "sppm checkpoint";
}  // namespace

Image sppmImage(const std::vector<SppmPixel>& entries, int width, int height, uint32_t perPixel, uint64_t iterations,
                uint64_t photons, uint64_t ldCount) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0};
            const size_t first = (size_t(y) * size_t(width) + size_t(x)) * perPixel;
            for (uint32_t j = 0; j < perPixel; ++j) {
                double L[3];
                sppmPixelRadiance(entries[first + j], iterations, photons, ldCount, L);
                for (int c = 0; c < 3; ++c) sum[c] += L[c];
            }
            const double inv = 1.0 / double(perPixel);
            image.set(x, y, Spectrum(Float(sum[0] * inv), Float(sum[1] * inv), Float(sum[2] * inv)));
        }
    return image;
}

void writeSppmCheckpoint(std::ostream& out, const SppmCheckpoint& c) {
    BinaryWriter w(out, kWhat);
    w.u32(kMagic);
    w.u32(kVersion);
    w.u32(uint32_t(c.width));
    w.u32(uint32_t(c.height));
    w.u32(c.perPixel);
    w.u64(c.photonCount);
    w.f64(c.alpha);
    w.f64(c.initialRadius);
    w.u64(c.iterations);
    w.array(c.pixels.data(), c.pixels.size());
    w.u64(w.hash());
}

SppmCheckpoint readSppmCheckpoint(std::istream& in, const SppmCheckpoint& expected) {
    BinaryReader r(in, kWhat);
    if (r.u32() != kMagic) throw Error(std::string(kWhat) + ": not an SPPM payload");
    if (r.u32() != kVersion) throw Error(std::string(kWhat) + ": unsupported version");
    SppmCheckpoint c;
    c.width = int(r.u32());
    c.height = int(r.u32());
    c.perPixel = r.u32();
    c.photonCount = r.u64();
    c.alpha = r.f64();
    c.initialRadius = r.f64();
    c.iterations = r.u64();
    const uint64_t n = r.u64();
    if (n != uint64_t(c.width) * uint64_t(c.height) * c.perPixel || n > (uint64_t(1) << 32))
        throw Error(std::string(kWhat) + ": damaged (pixel count)");
    c.pixels.resize(size_t(n));
    r.bytes(c.pixels.data(), size_t(n) * sizeof(SppmPixel));
    r.checkHash();
    if (c.width != expected.width || c.height != expected.height)
        throw Error(std::string(kWhat) + ": image size " + std::to_string(c.width) + "x" + std::to_string(c.height) +
                    " differs from this render's " + std::to_string(expected.width) + "x" +
                    std::to_string(expected.height));
    if (c.perPixel != expected.perPixel)
        throw Error(std::string(kWhat) + ": " + std::to_string(c.perPixel) + " hitpoints per pixel differ from " +
                    std::to_string(expected.perPixel));
    if (c.photonCount != expected.photonCount)
        throw Error(std::string(kWhat) + ": photon_count " + std::to_string(c.photonCount) + " differs from " +
                    std::to_string(expected.photonCount));
    if (c.alpha != expected.alpha) throw Error(std::string(kWhat) + ": alpha differs");
    if (c.initialRadius != expected.initialRadius) throw Error(std::string(kWhat) + ": initial_radius differs");
    for (const SppmPixel& p : c.pixels)
        if (!(p.radius > 0) || !(p.n >= 0) || !std::isfinite(p.radius))
            throw Error(std::string(kWhat) + ": damaged (pixel statistics)");
    return c;
}

}  // namespace caustica
