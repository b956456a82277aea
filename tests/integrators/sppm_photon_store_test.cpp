// SppmPhotonBatch (integrators/sppm/sppm_photon_store.h): photons written in batches land in
// consecutive slots with their Morton keys and slots, every photon is counted (overflow
// included) but none is written past the capacity, and many paths appending at once on several
// threads store each photon exactly once.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "caustica/integrators/sppm/sppm_photon_store.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"

namespace caustica::test {
namespace {

SppmPhoton photonAt(uint32_t id) {
    const Float x = Float(id % 17) / 17, y = Float(id % 5) / 5, z = Float(id % 3) / 3;
    return SppmPhoton{Vec3f(x, y, z), Vec3f(0, 1, 0), Vec3f(0, 1, 0), Spectrum(Float(id)), id};
}

struct Stored {
    std::vector<SppmPhoton> photons;
    std::vector<uint32_t> keys, order;
    uint64_t counted = 0;
};

/// `paths` paths, path i appending photonsOf(i) photons (depth = a unique id), on `threads`.
template <class Count>
Stored store(uint32_t paths, Count photonsOf, uint64_t capacity, int threads) {
    Buffer<SppmPhoton> photons(Device::cpu(), size_t(capacity));
    Buffer<uint32_t> keys(Device::cpu(), size_t(capacity)), order(Device::cpu(), size_t(capacity));
    Buffer<uint64_t> counter(Device::cpu(), 1);
    counter.copyFromHost(std::vector<uint64_t>{0});
    SppmPhotonStore s;
    s.photons = photons.data();
    s.capacity = capacity;
    s.counter = counter.data();
    s.keys = keys.data();
    s.order = order.data();
    s.lo = Vec3f(0);
    s.invExtent = Vec3f(1);
    tbb::task_arena(threads).execute([&] {
        launch(
            CpuExec{}, "test.store", paths,
            [=](size_t i) {
                SppmPhotonBatch batch(s);
                for (uint32_t j = 0; j < photonsOf(uint32_t(i)); ++j) batch.add(photonAt(uint32_t(i) * 100 + j));
                batch.flush();
            },
            1);
    });
    Stored out;
    out.counted = counter.toHost()[0];
    const size_t written = size_t(std::min(out.counted, capacity));
    out.photons = photons.toHost();
    out.keys = keys.toHost();
    out.order = order.toHost();
    out.photons.resize(written);
    out.keys.resize(written);
    out.order.resize(written);
    return out;
}

TEST(SppmPhotonStore, OnePathsPhotonsLandInConsecutiveSlotsWithKeysAndSlots) {
    // 11 photons: batches of kSppmPhotonBatch, the rest at the final flush.
    const Stored s = store(1, [](uint32_t) { return 11u; }, 64, 1);
    ASSERT_EQ(s.counted, 11u);
    for (uint32_t j = 0; j < 11; ++j) {
        EXPECT_EQ(s.photons[j].depth, j);
        EXPECT_EQ(s.photons[j].flux.r, Float(j));
        EXPECT_EQ(s.keys[j], sppmMorton(photonAt(j).p, Vec3f(0), Vec3f(1)));
        EXPECT_EQ(s.order[j], j);
    }
}

TEST(SppmPhotonStore, OverflowIsCountedButNotWritten) {
    const Stored s = store(3, [](uint32_t) { return 5u; }, 7, 1);
    EXPECT_EQ(s.counted, 15u);  // the caller retraces with a store of at least 15
    EXPECT_EQ(s.photons.size(), 7u);
}

TEST(SppmPhotonStore, ManyPathsOnTwoThreadsStoreEveryPhotonOnce) {
    const auto count = [](uint32_t i) { return i % 7; };  // 0..6 photons, some paths none
    const uint32_t paths = 5000;
    uint64_t expected = 0;
    for (uint32_t i = 0; i < paths; ++i) expected += count(i);
    for (int threads : {1, 2}) {
        const Stored s = store(paths, count, expected, threads);
        ASSERT_EQ(s.counted, expected);
        std::vector<uint32_t> ids;
        for (size_t slot = 0; slot < s.photons.size(); ++slot) {
            ids.push_back(s.photons[slot].depth);
            EXPECT_EQ(s.order[slot], uint32_t(slot));
            EXPECT_EQ(s.keys[slot], sppmMorton(s.photons[slot].p, Vec3f(0), Vec3f(1)));
        }
        std::sort(ids.begin(), ids.end());
        std::vector<uint32_t> want;
        for (uint32_t i = 0; i < paths; ++i)
            for (uint32_t j = 0; j < count(i); ++j) want.push_back(i * 100 + j);
        std::sort(want.begin(), want.end());
        EXPECT_EQ(ids, want) << threads << " threads";
    }
}

TEST(SppmPhotonStore, WithoutKeysOnlyThePhotonsAreWritten) {
    Buffer<SppmPhoton> photons(Device::cpu(), 4);
    Buffer<uint64_t> counter(Device::cpu(), 1);
    counter.copyFromHost(std::vector<uint64_t>{0});
    SppmPhotonStore s;
    s.photons = photons.data();
    s.capacity = 4;
    s.counter = counter.data();
    SppmPhotonBatch batch(s);
    batch.add(photonAt(3));
    batch.flush();
    batch.flush();  // nothing held: no slot reserved
    EXPECT_EQ(counter.toHost()[0], 1u);
    EXPECT_EQ(photons.toHost()[0].depth, 3u);
}

}  // namespace
}  // namespace caustica::test
