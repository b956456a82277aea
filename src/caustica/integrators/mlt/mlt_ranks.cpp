#include "caustica/integrators/mlt/mlt_ranks.h"

#include <cstring>
#include <span>

#include "caustica/util/error.h"

namespace caustica {

void gatherMltBootstrap(Communicator& comm, std::vector<float>& importance, std::vector<uint32_t>& pixel) {
    static_assert(sizeof(float) == 4 && sizeof(uint32_t) == 4);
    const bool withPixels = !pixel.empty();
    // n importances, then (with pixels) n pixels.
    std::vector<uint8_t> bytes(4 * importance.size() * (withPixels ? 2 : 1));
    std::memcpy(bytes.data(), importance.data(), 4 * importance.size());
    if (withPixels) std::memcpy(bytes.data() + 4 * importance.size(), pixel.data(), 4 * pixel.size());
    const std::vector<std::vector<uint8_t>> parts = comm.allGather(bytes);
    importance.clear();
    pixel.clear();
    for (const std::vector<uint8_t>& part : parts) {
        const size_t n = part.size() / (withPixels ? 8 : 4);
        if (part.size() != n * (withPixels ? 8 : 4)) throw Error("MLT: a rank's bootstrap samples arrived damaged");
        const size_t at = importance.size();
        importance.resize(at + n);
        std::memcpy(importance.data() + at, part.data(), 4 * n);
        if (withPixels) {
            pixel.resize(at + n);
            std::memcpy(pixel.data() + at, part.data() + 4 * n, 4 * n);
        }
    }
}

void sumMltIterationCounts(Communicator& comm, MltIterationCounts& counts) {
    // Counts below 2^53 are exact in doubles.
    double v[3] = {double(counts.accepted), double(counts.largeSteps), counts.largeStepSum};
    comm.sum(std::span<double>(v));
    counts.accepted = uint64_t(v[0]);
    counts.largeSteps = uint64_t(v[1]);
    counts.largeStepSum = v[2];
}

}  // namespace caustica
