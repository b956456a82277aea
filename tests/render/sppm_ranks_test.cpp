// The photon mappers over ranks (render/sppm_session.cpp, InProcessGroup: ranks as threads):
// each rank traces its share of every iteration's photons and the photon sums (64-bit fixed
// point) are summed over the ranks before the update, so the image of 2 and 3 ranks equals one
// process's to the bit, on every rank, for sppm (both directions) and ppm; a checkpoint saved on
// 2 ranks and loaded on 2 continues as the uninterrupted render; the exchange's bytes are counted.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "caustica/io/scene_loader.h"
#include "common/rank_sessions.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

using Params = std::vector<std::pair<std::string, std::string>>;

caustica::RenderRequest photonRequest(const char* integrator, uint64_t seed, const Params& params) {
    caustica::RenderRequest r;
    r.integrator = integrator;
    r.seed = seed;
    r.device = "cpu";
    for (const auto& [name, value] : params)
        r.integratorParams.push_back({name, IntegratorParam::Kind::Text, value, "--" + name});
    return r;
}

Scene causticScene(int size) {
    const std::string s = std::to_string(size);
    return loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", s}, {"height", s}});
}

/// Every rank's image after `iterations` steps (index: rank).
std::vector<Image> renderOnRanks(const RankRig& rig, int ranks, int iterations) {
    std::vector<Image> images(static_cast<size_t>(ranks));
    rig.run(ranks, [&](IntegratorSession& session, Communicator& comm) {
        for (int i = 0; i < iterations; ++i) session.step(0);
        images[size_t(comm.rank())] = session.develop();
    });
    return images;
}

double imageSum(const Image& image) {
    double sum = 0;
    for (float v : image.rgb) sum += v;
    return sum;
}

void expectRanksEqualOneProcess(const caustica::RenderRequest& request, int iterations) {
    const Scene scene = causticScene(20);
    const RankRig rig(scene, request);
    const Image one = renderOnRanks(rig, 1, iterations)[0];
    ASSERT_GT(imageSum(one), 0);
    for (int ranks : {2, 3})
        for (const Image& image : renderOnRanks(rig, ranks, iterations))
            EXPECT_TRUE(image.rgb == one.rgb) << ranks << " ranks: the image differs from one process's";
}

TEST(SppmRanks, DepositEqualsOneProcessToTheBit) {
    expectRanksEqualOneProcess(photonRequest("sppm", 5, {{"photon_count", "3001"}}), 3);
}

TEST(SppmRanks, GatherEqualsOneProcessToTheBit) {
    expectRanksEqualOneProcess(photonRequest("sppm", 6, {{"photon_count", "2048"}, {"direction", "gather"}}), 2);
}

TEST(SppmRanks, PpmEqualsOneProcessToTheBit) {
    expectRanksEqualOneProcess(photonRequest("ppm", 7, {{"photon_count", "2048"}, {"hitpoints", "2"}}), 3);
}

TEST(SppmRanks, CheckpointOfTwoRanksContinuesAsTheUninterruptedRender) {
    const Scene scene = causticScene(16);
    const RankRig rig(scene, photonRequest("sppm", 9, {{"photon_count", "2048"}}));
    const std::vector<Image> whole = renderOnRanks(rig, 2, 4);
    std::string file;
    rig.run(2, [&](IntegratorSession& session, Communicator& comm) {
        for (int i = 0; i < 2; ++i) session.step(0);
        const std::string mine = saveOnRanks(session, comm);
        if (comm.isRoot()) file = mine;
    });
    std::vector<Image> resumed(2);
    rig.run(2, [&](IntegratorSession& session, Communicator& comm) {
        loadOnRanks(session, file);
        EXPECT_EQ(session.samplesPerPixel(), 2);
        for (int i = 0; i < 2; ++i) session.step(0);
        resumed[size_t(comm.rank())] = session.develop();
    });
    for (const Image& image : resumed) EXPECT_TRUE(image.rgb == whole[0].rgb) << "the resumed image differs";
}

TEST(SppmRanks, BytesSentPerIterationAreReported) {
    const Scene scene = causticScene(8);
    const RankRig rig(scene, photonRequest("sppm", 3, {{"photon_count", "256"}}));
    // Per rank: bytes_sent_per_iteration, bytes_sent (the whole run: two iterations).
    auto bytesSent = [&](int ranks) {
        std::vector<std::pair<double, double>> bytes(static_cast<size_t>(ranks), {0.0, 0.0});
        rig.run(ranks, [&](IntegratorSession& session, Communicator& comm) {
            session.step(0);
            session.step(0);
            for (const auto& [key, value] : session.statsJson()) {
                if (key == "bytes_sent_per_iteration") bytes[size_t(comm.rank())].first = std::stod(value);
                if (key == "bytes_sent") bytes[size_t(comm.rank())].second = std::stod(value);
            }
        });
        return bytes;
    };
    EXPECT_EQ(bytesSent(1)[0], std::make_pair(0.0, 0.0));
    // 8x8 entries of three flux sums and a count, 8 bytes each, from every rank (InProcessGroup
    // counts the bytes a rank contributes).
    for (const auto& [perIteration, whole] : bytesSent(2)) {
        EXPECT_EQ(perIteration, 8 * 8 * 4 * 8);
        EXPECT_EQ(whole, 2 * 8 * 8 * 4 * 8);
    }
}

}  // namespace
}  // namespace caustica::test
