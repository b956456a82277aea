// mlt_checkpoint.h — the resumable MLT checkpoint the driver (mlt_driver.h) writes and reads on
// every device. Arrays travel through host copies
// (Buffer::toHost / copyFromHost), so device buffers work as host ones do.
//
//   char[8] "CAMLTCK1" | u32 version | u64 values that must match (mltCheckpointKeys)
//   counters and timings | b (sum, count, b0) | pixel weights | chain store (fine, coarse, float)
//   | film positions, F, I, U of the chains | splat sums | the splats of the unfinished batch
//   | u64 FNV-1a hash of all before it
//
// The chain store is written chain-major (coordinate slot s of chain c at c * slots + s, the CPU
// driver's layout); a driver keeping another layout converts with mltTransposeCells.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_impl.h"

namespace caustica {

/// A value a checkpoint must agree on with the render resuming it; a mismatch is an error naming
/// the setting and both values, as `show` writes them (nullptr: a decimal number).
struct MltCheckpointKey {
    const char* name;
    uint64_t value;
    std::string (*show)(uint64_t) = nullptr;
};
using MltCheckpointKeys = std::vector<MltCheckpointKey>;
MltCheckpointKeys mltCheckpointKeys(const MltStepParams& params, const MltSettings& settings, uint32_t storedDims,
                                    const Filter& filter);

/// The value `name` was saved with, read from a checkpoint's header once the whole file has
/// checked out (magic, version, checksum); nullopt for a file that does not, or a name not among
/// `keys` (this render's keys: their order is the file's). Lets a resume take a setting it leaves
/// to its default from the checkpoint; readMltCheckpoint still verifies everything after that.
std::optional<uint64_t> peekMltCheckpointKey(std::istream& in, const MltCheckpointKeys& keys, std::string_view name);

/// Host copy of everything a checkpoint holds.
struct MltCheckpoint {
    MltStats stats;                   // counters and timings; b is b.b()
    MltNormalisation b;
    std::vector<float> pixelWeight;   // relative target: one per pixel; else empty
    std::vector<uint8_t> fine;        // compact store (3 bytes per slot), chain-major
    std::vector<uint16_t> coarse;     // compact store, chain-major
    std::vector<float> values;        // float store, chain-major
    std::vector<Vec2f> pos;           // per chain: film position, F, I, U
    std::vector<Spectrum> value;
    std::vector<float> importance;
    std::vector<uint16_t> usedDims;
    std::vector<double> image;        // kMltValuesPerPixel splat sums per pixel
    std::vector<MltSplat> pendingSplats;  // the unfinished batch: (iterations % batch) x n (k + 1)
};

/// Element counts a checkpoint's arrays must have to fit a renderer (the chains' per-chain
/// arrays all have `chains` elements).
struct MltCheckpointSizes {
    size_t pixelWeights = 0, fine = 0, coarse = 0, values = 0, chains = 0, image = 0;
    size_t splatsPerIteration = 0;  // the unfinished batch has (iterations % splatBatch) x this
    uint32_t splatBatch = 1;
};
/// The sizes for a renderer with these settings, pixels and buffers, whose chain store has
/// `fine`, `coarse` and `values` elements (0 for arrays its store does not have).
MltCheckpointSizes mltCheckpointSizes(const MltSettings& settings, uint32_t pixels, const MltChainBuffers& buffers,
                                      size_t fine, size_t coarse, size_t values);

/// The driver-independent part of a checkpoint: `stats`, `b` and the chains' buffers, downloaded.
/// The driver adds its pixel weights and chain store.
MltCheckpoint mltCheckpointOf(const MltStats& stats, const MltNormalisation& b, const MltChainBuffers& buffers);

void writeMltCheckpoint(std::ostream& out, const MltCheckpointKeys& keys, const MltCheckpoint& checkpoint);

/// Reads and verifies a whole checkpoint (magic, version, keys, array sizes, hash) into host
/// copies; throws caustica::Error ("MLT checkpoint: ...") on anything wrong, before the caller
/// has changed anything. Its stats are `current` with the saved counters and timings.
MltCheckpoint readMltCheckpoint(std::istream& in, const MltCheckpointKeys& keys, const MltCheckpointSizes& sizes,
                                const MltStats& current);

/// Commits the driver-independent part of a verified checkpoint: stats (b included), b and the
/// chains' buffers (uploaded). The driver commits its pixel weights and chain store.
void restoreMltCheckpoint(const MltCheckpoint& checkpoint, MltStats& stats, MltNormalisation& b,
                          MltChainBuffers& buffers);

/// `in` as a rows x cols matrix of cells of `width` elements (row-major), transposed: cell
/// (r, c) moves to (c, r). Turns a dimension-major store (slots x chains) into a chain-major
/// one and back. An array of another size (a placeholder element where rows x cols is 0) is
/// returned unchanged.
template <class T>
std::vector<T> mltTransposeCells(const std::vector<T>& in, size_t rows, size_t cols, size_t width) {
    if (in.size() != rows * cols * width) return in;
    std::vector<T> out(in.size());
    for (size_t r = 0; r < rows; ++r)
        for (size_t c = 0; c < cols; ++c)
            for (size_t k = 0; k < width; ++k) out[(c * rows + r) * width + k] = in[(r * cols + c) * width + k];
    return out;
}

}  // namespace caustica
