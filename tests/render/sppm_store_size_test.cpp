// The photon store of direction "gather" (integrators/sppm/sppm_driver.h): the first store is
// sized by a pilot of the first pass, so cornell-water's first pass is not traced twice any more;
// a store that turns out too small (presizePhotonStore) is grown and the pass traced again with
// the same photons, and the image is the same to the bit either way.
#include <gtest/gtest.h>

#include <cstring>
#include <utility>

#include "caustica/accel/accel.h"
#include "caustica/integrators/sppm/sppm_driver.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/launch.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

TEST(SppmPhotonStoreSize, ATooSmallStoreIsGrownAndTheImageIsTheSame) {
    const Scene scene = loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "32"}, {"height", "32"}});
    const Accel accel(scene, AccelKind::Bvh);
    SppmSettings settings;
    settings.photonCount = 1 << 14;  // cornell-water stores about 2.5 photons a path
    const auto render = [&](uint64_t presize) {
        auto driver = makeSppmDriver<CpuExec>(scene, accel, settings, 7);
        driver->presizePhotonStore(presize);
        for (int i = 0; i < 3; ++i) driver->iterate();
        return std::make_pair(driver->develop(), driver->stats().photonRetraces);
    };
    const auto [piloted, pilotedRetraces] = render(0);  // the pilot: 4096 of the 16384 paths
    const auto [grown, grownRetraces] = render(16);
    // The pilot's estimate is off by about 1% here; the store holds a quarter more.
    EXPECT_EQ(pilotedRetraces, 0u);
    EXPECT_EQ(grownRetraces, 1u);  // grown once, to the first pass's count plus a quarter
    ASSERT_TRUE(piloted.sameSize(grown));
    EXPECT_EQ(std::memcmp(piloted.rgb.data(), grown.rgb.data(), piloted.rgb.size() * sizeof(float)), 0);
}

}  // namespace
}  // namespace caustica::test
