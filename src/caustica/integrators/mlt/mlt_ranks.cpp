#include "caustica/integrators/mlt/mlt_ranks.h"

#include <algorithm>
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

void MltPendingCounts::add(const MltIterationCounts& counts) {
    accepted_ += counts.accepted;
    largeSteps_ += counts.largeSteps;
    largeStepSums_.push_back(counts.largeStepSum);
}

void MltPendingCounts::gather(Communicator& comm, MltStats& stats, MltNormalisation& b) {
    // Counts below 2^53 are exact in doubles; the per-iteration sums are summed element-wise in
    // rank order, as each iteration's sum over the ranks was.
    std::vector<double> v(2 + largeStepSums_.size());
    v[0] = double(accepted_);
    v[1] = double(largeSteps_);
    std::copy(largeStepSums_.begin(), largeStepSums_.end(), v.begin() + 2);
    comm.sum(std::span<double>(v));
    stats.accepted += uint64_t(v[0]);
    stats.largeSteps += uint64_t(v[1]);
    // b.count only ever adds integers (exact), so the total at once equals the per-iteration adds.
    for (size_t t = 2; t < v.size(); ++t) b.add(v[t], 0);
    b.count += v[1];
    stats.b = b.b();
    clear();
}

void MltPendingCounts::clear() {
    accepted_ = largeSteps_ = 0;
    largeStepSums_.clear();
}

uint64_t mltIterationsPerRankStep(const MltSettings& settings) {
    const uint64_t perIteration = std::max<uint64_t>(1, uint64_t(settings.chains) * settings.proposals);
    return std::max<uint64_t>(1, (kMltRankStepProposals + perIteration - 1) / perIteration);
}

}  // namespace caustica
