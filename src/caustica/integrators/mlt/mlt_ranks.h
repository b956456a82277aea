// mlt_ranks.h — what MLT exchanges between the ranks its chains are split over (host code of the
// drivers, mlt_driver.h): the bootstrap samples, gathered so that every rank plans one process's
// b and chain starts, and the iterations' counters, summed so that b (refined by the large steps)
// and the counters are the whole render's on every rank. The counters are summed only where the
// whole render's are read (develop, checkpoint, statistics), not every iteration: the chains'
// kernels read the bootstrap's b0 alone, so nothing between those points needs them.
#pragma once

#include <cstdint>
#include <vector>

#include "caustica/distributed/communicator.h"
#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_impl.h"

namespace caustica {

/// Replaces this rank's bootstrap samples (importance, and pixel unless empty) by every rank's,
/// in rank order: all M samples in global order when each rank traced its share (mltShareOf).
void gatherMltBootstrap(Communicator& comm, std::vector<float>& importance, std::vector<uint32_t>& pixel);

/// This rank's counters of the iterations since the ranks last summed them (accepted moves, large
/// steps and, per iteration, the large steps' importance sum). gather() adds every rank's to the
/// render's statistics and b exactly as a sum over the ranks after every iteration did: the
/// per-iteration importance sums are summed over the ranks element-wise in rank order and then
/// added to b one iteration after the other (the same double additions in the same order, so b and
/// the image do not depend on where the ranks meet; the counts are integers, exact in any order).
class MltPendingCounts {
public:
    /// An iteration's counters on this rank (rays are not kept: they stay the rank's).
    void add(const MltIterationCounts& counts);
    uint64_t iterations() const { return largeStepSums_.size(); }
    /// Collective: every rank must call it after the same iterations (the chains step in lock
    /// step, so the ranks' pending iterations agree). Adds the sums to `stats` and `b`, clears.
    void gather(Communicator& comm, MltStats& stats, MltNormalisation& b);
    /// Forgets them (a bootstrap or a loaded checkpoint replaces the counters).
    void clear();

private:
    uint64_t accepted_ = 0, largeSteps_ = 0;
    std::vector<double> largeStepSums_;  // one per pending iteration
};

/// Iterations the ranks run between two gathers at most, whatever else happens, so that the
/// pending per-iteration sums stay small (8 bytes each: 32 KiB).
inline constexpr uint64_t kMltMostPendingIterations = 4096;

/// Iterations of one step of a render over several ranks: enough for about kMltRankStepProposals
/// proposals of all chains together (at least one). The ranks agree on the budget, Ctrl-C and
/// checkpoints once per step (render_run.cpp), so one iteration a step made them wait for each
/// other every iteration; a step of many lets a rank's slow iteration be made up by a fast one.
inline constexpr uint64_t kMltRankStepProposals = uint64_t(1) << 16;
uint64_t mltIterationsPerRankStep(const MltSettings& settings);

}  // namespace caustica
