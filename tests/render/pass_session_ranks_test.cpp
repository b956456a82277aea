// path/direct/whitted over several ranks (render/pass_session.cpp), with the ranks as threads
// (InProcessGroup): every rank ends with the single-process image, bit for bit, including a last
// pass cut short by the sample budget; counters count each rank's share.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "caustica/distributed/in_process_group.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/renderer.h"

namespace caustica::test {
namespace {

const std::string kScene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box/scene.xml";

RenderRequest request(const std::string& integrator, int spp, int sppPerPass) {
    RenderRequest r;
    r.integrator = integrator;
    r.samplesPerPixel = spp;
    r.samplesPerPass = sppPerPass;
    r.seed = 11;
    r.device = "cpu";
    r.resolution = std::make_pair(12, 9);
    return r;
}

std::vector<float> renderAlone(const RenderRequest& r) {
    Renderer renderer(loadScene(kScene), r);
    while (!renderer.finished()) renderer.step();
    return renderer.develop().rgb;
}

struct RankResult {
    std::vector<float> image;
    double spp = 0;
    uint64_t samples = 0, totalSamples = 0;
};

std::vector<RankResult> renderOverRanks(const RenderRequest& r, int ranks) {
    InProcessGroup group(ranks);
    std::vector<RankResult> results(static_cast<size_t>(ranks));
    group.run([&](Communicator& comm) {
        Renderer renderer(loadScene(kScene), r, nullptr, comm);
        while (!renderer.finished()) renderer.step();
        RankResult& mine = results[size_t(comm.rank())];
        mine.image = renderer.develop().rgb;
        mine.spp = renderer.progress().samplesPerPixel;
        mine.samples = renderer.session().counters().samples;
        mine.totalSamples = renderer.stats().samples;  // collective: summed over the ranks
    });
    return results;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(PassSessionRanks, EveryRankHoldsTheSingleProcessImageBitForBit) {
    for (const char* integrator : {"path", "direct", "whitted"})
        for (int ranks : {2, 3}) {
            SCOPED_TRACE(std::string(integrator) + " over " + std::to_string(ranks) + " ranks");
            // 7 spp in passes of 2: the last pass (1 spp) falls on a rank in the middle of a step.
            const RenderRequest r = request(integrator, 7, 2);
            const std::vector<float> alone = renderAlone(r);
            uint64_t sum = 0;
            for (const RankResult& rank : renderOverRanks(r, ranks)) {
                EXPECT_TRUE(sameBits(rank.image, alone));
                EXPECT_EQ(rank.spp, 7);
                EXPECT_EQ(rank.totalSamples, uint64_t(12 * 9 * 7));
                sum += rank.samples;
            }
            EXPECT_EQ(sum, uint64_t(12 * 9 * 7));  // each sample rendered once, by one rank
        }
}

TEST(PassSessionRanks, ASampleBudgetBelowOneStepLeavesSomeRanksIdle) {
    // 3 spp in passes of 2 over 3 ranks: ranks 0 and 1 render, rank 2 waits for the next step.
    const RenderRequest r = request("path", 3, 2);
    const std::vector<float> alone = renderAlone(r);
    const std::vector<RankResult> results = renderOverRanks(r, 3);
    for (const RankResult& rank : results) EXPECT_TRUE(sameBits(rank.image, alone));
    EXPECT_EQ(results[2].samples, 0u);
}

}  // namespace
}  // namespace caustica::test
