// mlt_ranks.h — what MLT exchanges between the ranks its chains are split over (host code of the
// drivers, mlt_driver.h): the bootstrap samples, gathered so that every rank plans one process's
// b and chain starts, and each iteration's counters, summed so that b (refined by the large
// steps) and the counters are the whole render's on every rank.
#pragma once

#include <cstdint>
#include <vector>

#include "caustica/distributed/communicator.h"
#include "caustica/integrators/mlt/mlt_buffers.h"

namespace caustica {

/// Replaces this rank's bootstrap samples (importance, and pixel unless empty) by every rank's,
/// in rank order: all M samples in global order when each rank traced its share (mltShareOf).
void gatherMltBootstrap(Communicator& comm, std::vector<float>& importance, std::vector<uint32_t>& pixel);

/// Sums the iteration's accepted moves and large steps (count and importance sum) over the ranks;
/// rays stay this rank's.
void sumMltIterationCounts(Communicator& comm, MltIterationCounts& counts);

}  // namespace caustica
