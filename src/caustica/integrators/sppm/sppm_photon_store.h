// sppm_photon_store.h — how direction "gather" appends photons to the store (CA_HD: CPU and GPU).
// A photon path keeps its photons in a small batch and writes the batch with ONE slot
// reservation (one atomic on the shared counter per batch, a path stores about 2.5 photons on
// cornell-water) instead of one per photon, so that the counter's cache line and the store's
// lines are not fought over by every photon of every thread, and a path's photons land side by
// side. The batch also writes each photon's Morton key (the sort key of the cell order) and its
// slot (the sort's value), so no pass reads the store back for them.
//
// The photons' order in the store is not part of the result: the gather sums integer units
// (SppmFixedPoint), so any order gives the same image bits.
#pragma once

#include <cstdint>

#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/integrators/sppm/sppm_photon.h"

namespace caustica {

/// Where a photon pass writes: `capacity` records (photons beyond it are counted, not written,
/// so that the caller sees the overflow and traces again with a larger store); with `keys` set,
/// keys[slot] = the photon's Morton code in the box (lo, invExtent) and order[slot] = slot.
struct SppmPhotonStore {
    SppmPhoton* photons = nullptr;
    uint64_t capacity = 0;
    uint64_t* counter = nullptr;  // photons appended so far (all of them, overflow included)
    uint32_t* keys = nullptr;     // optional
    uint32_t* order = nullptr;    // with keys
    Vec3f lo, invExtent;          // the Morton box, with keys
};

/// Photons per batch: flushed when full and when the path ends (a path that stores more
/// reserves more than once).
inline constexpr uint32_t kSppmPhotonBatch = 4;

/// The photons of one path on their way to an SppmPhotonStore.
class SppmPhotonBatch {
public:
    CA_HD explicit SppmPhotonBatch(const SppmPhotonStore& store) : store_(store) {}
    SppmPhotonBatch(const SppmPhotonBatch&) = delete;
    SppmPhotonBatch& operator=(const SppmPhotonBatch&) = delete;

    CA_HD void add(const SppmPhoton& photon) {
        photons_[count_++] = photon;
        if (count_ == kSppmPhotonBatch) flush();
    }

    /// Reserves slots for the photons held and writes those that fit.
    CA_HD void flush() {
        if (count_ == 0) return;
        const uint64_t first = sppmAtomicFetchAdd(store_.counter, count_);
        for (uint32_t j = 0; j < count_; ++j) {
            const uint64_t slot = first + j;
            if (slot >= store_.capacity) break;
            store_.photons[slot] = photons_[j];
            if (store_.keys) {
                store_.keys[slot] = sppmMorton(photons_[j].p, store_.lo, store_.invExtent);
                store_.order[slot] = uint32_t(slot);
            }
        }
        count_ = 0;
    }

private:
    SppmPhotonStore store_;
    SppmPhoton photons_[kSppmPhotonBatch];
    uint32_t count_ = 0;
};

}  // namespace caustica
