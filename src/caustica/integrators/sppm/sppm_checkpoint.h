// sppm_checkpoint.h — the photon mappers' checkpoint payload and image (host code): every pixel's
// (ppm: hitpoint's) statistics (Ld, τ, N, R) and the iteration count, which is also the position of every random
// stream (eye and photon streams are keyed by the iteration). Self-checking as the film's and
// MLT's payloads: util/binary_io.h with a trailing FNV-1a hash; the settings that must match
// (size, photon count, α, initial radius) are checked by value. A load reads and verifies the
// whole payload before it returns anything.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "caustica/film/image.h"
#include "caustica/integrators/sppm/sppm_kernel.h"

namespace caustica {

struct SppmCheckpoint {
    int width = 0, height = 0;
    uint32_t perPixel = 1;  // statistics entries per pixel (ppm: hitpoints)
    uint64_t photonCount = 0;
    double alpha = 0, initialRadius = 0;
    uint64_t iterations = 0;
    std::vector<SppmPixel> pixels;
};

void writeSppmCheckpoint(std::ostream& out, const SppmCheckpoint& c);
/// Reads a payload and checks it against `expected`'s width, height, photon count, α and
/// initial radius; throws caustica::Error naming the first mismatch or the damage.
SppmCheckpoint readSppmCheckpoint(std::istream& in, const SppmCheckpoint& expected);

/// The image of the statistics: per pixel the mean over its `perPixel` entries of
/// Ld / ldCount + τ / (iterations · photons · π R²) (sppm_kernel.h: sppmPixelRadiance).
Image sppmImage(const std::vector<SppmPixel>& entries, int width, int height, uint32_t perPixel, uint64_t iterations,
                uint64_t photons, uint64_t ldCount);

}  // namespace caustica
