// mlt_rank_checkpoint.h — an MLT checkpoint of chains split over ranks (mlt_impl.h: MltShare):
// the ranks' parts merged into the whole render that rank 0 writes, and a rank's part taken back
// out of it on a resume. The whole render has one process's layout (every chain in global order,
// the unfinished splat batch slot by slot), except its splat sums: one film per rank, in rank
// order, so that every rank resumes with its own sums and the resumed render adds them up in the
// same order as the uninterrupted one (the same bits). One rank: exactly one process's file.
#pragma once

#include <cstddef>
#include <vector>

#include "caustica/integrators/mlt/mlt_checkpoint.h"

namespace caustica {

/// Elements per chain of the chain store's arrays (0 for an array the store does not have; the
/// drivers keep a one-element placeholder for an empty array, which is not split).
struct MltChainWidths {
    size_t fine = 0, coarse = 0, values = 0;
    size_t splats = 1;  // splats per chain and iteration: proposals + 1
};

/// The whole render from every rank's part (index: rank; each part with that rank's chains and
/// film): chains concatenated, the unfinished batch interleaved slot by slot, the films one after
/// another, rays summed; the other counters, b and the pixel weights are rank 0's (equal on every
/// rank).
MltCheckpoint mergeMltCheckpoints(const std::vector<MltCheckpoint>& parts, const MltChainWidths& widths);

/// Rank `rank`'s part of the whole render `whole` (`ranks` films, `totalChains` chains): its
/// chains `share`, its splats of the unfinished batch and its film.
MltCheckpoint mltCheckpointPart(const MltCheckpoint& whole, const MltChainWidths& widths, MltShare share,
                                uint32_t totalChains, int rank, int ranks);

}  // namespace caustica
