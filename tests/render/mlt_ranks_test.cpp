// MLT over ranks (render/mlt_session.cpp, integrators/mlt/, InProcessGroup: ranks as threads):
// the bootstrap's samples are split and gathered, so b and the chain starts are one process's;
// each rank steps the chains of its global indices, so every chain moves as it does in one
// process, and the image of 2 and 3 ranks equals one process's up to the order of the splat and
// b sums (1e-5 relative per pixel); develop() is collective and gives every rank the image; a
// checkpoint saved on 2 ranks and loaded on 2 continues as the uninterrupted render to the bit
// (sort splats, which are deterministic); the same run twice gives the same bits. The iteration
// counters are summed over the ranks only where read (develop, save, statistics): b and the
// acceptance do not depend on where the ranks meet, and a step over ranks runs many iterations
// but ends an spp budget after the iteration one process would.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "caustica/io/scene_loader.h"
#include "caustica/util/error.h"
#include "common/rank_sessions.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

caustica::RenderRequest mltRequest(const char* chains, const char* splat = "sort") {
    caustica::RenderRequest r;
    r.integrator = "mlt";
    r.seed = 11;
    r.device = "cpu";
    const std::vector<std::pair<std::string, std::string>> params = {
        {"chains", chains}, {"luminance_samples", "4096"}, {"splat", splat}, {"max_depth", "6"}};
    for (const auto& [name, value] : params)
        r.integratorParams.push_back({name, IntegratorParam::Kind::Text, value, "--" + name});
    return r;
}

Scene causticScene() {
    return loadScene(sourcePath("scenes/cornell-water/scene.xml"), {{"width", "16"}, {"height", "12"}});
}

std::string statOf(const IntegratorSession& session, const std::string& key) {
    for (const auto& [k, v] : session.statsJson())
        if (k == key) return v;
    return "";
}

/// A budget below one iteration's mutations: the step runs exactly one iteration (a step over
/// ranks runs mltIterationsPerRankStep() iterations when it has no budget).
constexpr double kOneIteration = 1e-9;

struct RankResult {
    std::vector<Image> images;  // every rank's develop()
    std::string b;              // mlt_b after the bootstrap (rank 0)
};

/// The bootstrap and `iterations` iterations on `ranks` ranks.
RankResult renderOnRanks(const RankRig& rig, int ranks, int iterations) {
    RankResult result;
    result.images.resize(static_cast<size_t>(ranks));
    rig.run(ranks, [&](IntegratorSession& session, Communicator& comm) {
        session.step(0);
        if (comm.isRoot()) result.b = statOf(session, "mlt_b");
        for (int i = 0; i < iterations; ++i) session.step(kOneIteration);
        result.images[size_t(comm.rank())] = session.develop();
    });
    return result;
}

double mean(const Image& image) {
    double sum = 0;
    for (float v : image.rgb) sum += v;
    return sum / double(image.rgb.size());
}

/// The largest |a - b| over the pixels, relative to the pixel plus the image mean.
double largestDifference(const Image& a, const Image& b) {
    const double m = mean(b);
    double worst = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        worst = std::max(worst, std::fabs(double(a.rgb[i]) - double(b.rgb[i])) / (std::fabs(double(b.rgb[i])) + m));
    return worst;
}

TEST(MltRanks, BootstrapAndChainsAreOneProcesss) {
    const Scene scene = causticScene();
    for (const char* splat : {"sort", "atomic"}) {
        const RankRig rig(scene, mltRequest("48", splat));
        const RankResult one = renderOnRanks(rig, 1, 5);
        ASSERT_GT(mean(one.images[0]), 0);
        for (int ranks : {2, 3}) {
            const RankResult many = renderOnRanks(rig, ranks, 5);
            EXPECT_EQ(many.b, one.b) << ranks << " ranks: b differs from one process's";
            for (const Image& image : many.images) {
                EXPECT_TRUE(image.rgb == many.images[0].rgb) << "the ranks' images differ";
                EXPECT_LT(largestDifference(image, one.images[0]), 1e-5) << ranks << " ranks, " << splat;
                EXPECT_NEAR(mean(image), mean(one.images[0]), 1e-6 * mean(one.images[0]));
            }
        }
    }
}

TEST(MltRanks, OtherChainsGiveAnotherImage) {
    // The agreement above is not a matter of course: 49 chains (one more) move otherwise.
    const Scene scene = causticScene();
    const Image a = renderOnRanks(RankRig(scene, mltRequest("48")), 2, 5).images[0];
    const Image b = renderOnRanks(RankRig(scene, mltRequest("49")), 2, 5).images[0];
    EXPECT_GT(largestDifference(a, b), 1e-2);
}

TEST(MltRanks, CheckpointOfTwoRanksContinuesAsTheUninterruptedRender) {
    const Scene scene = causticScene();
    const RankRig rig(scene, mltRequest("40"));
    const RankResult whole = renderOnRanks(rig, 2, 6);
    std::string file;
    rig.run(2, [&](IntegratorSession& session, Communicator& comm) {
        session.step(0);  // the bootstrap
        for (int i = 0; i < 3; ++i) session.step(kOneIteration);  // 3 iterations: a splat batch pending
        const std::string mine = saveOnRanks(session, comm);
        if (comm.isRoot()) file = mine;
    });
    ASSERT_FALSE(file.empty());
    std::vector<Image> resumed(2);
    rig.run(2, [&](IntegratorSession& session, Communicator& comm) {
        loadOnRanks(session, file);
        for (int i = 0; i < 3; ++i) session.step(kOneIteration);
        resumed[size_t(comm.rank())] = session.develop();
    });
    for (const Image& image : resumed) EXPECT_TRUE(image.rgb == whole.images[0].rgb) << "the resumed image differs";
}

TEST(MltRanks, TheSameRunTwiceGivesTheSameBits) {
    const Scene scene = causticScene();
    const RankRig rig(scene, mltRequest("32"));
    EXPECT_TRUE(renderOnRanks(rig, 2, 3).images[0].rgb == renderOnRanks(rig, 2, 3).images[0].rgb);
}

TEST(MltRanks, CountersDoNotDependOnWhereTheRanksMeet) {
    const Scene scene = causticScene();
    const RankRig rig(scene, mltRequest("48"));
    // Accepted moves and b after 6 iterations: summed after every iteration, or once at the end.
    auto countersOn = [&](int ranks, bool meetEveryIteration) {
        std::vector<std::string> result(2);
        rig.run(ranks, [&](IntegratorSession& session, Communicator& comm) {
            session.step(0);
            for (int i = 0; i < 6; ++i) {
                session.step(kOneIteration);
                if (meetEveryIteration) session.gatherStatistics();
            }
            session.gatherStatistics();
            if (comm.isRoot()) result = {statOf(session, "mlt_accepted"), statOf(session, "mlt_b")};
        });
        return result;
    };
    const std::vector<std::string> everyIteration = countersOn(2, true), atTheEnd = countersOn(2, false);
    EXPECT_EQ(atTheEnd, everyIteration);  // to the bit: the same additions in the same order
    const std::vector<std::string> one = countersOn(1, false);
    EXPECT_EQ(atTheEnd[0], one[0]);  // the chains move as in one process
    ASSERT_FALSE(atTheEnd[1].empty());
    EXPECT_NEAR(std::stod(atTheEnd[1]), std::stod(one[1]), 1e-12 * std::stod(one[1]));
}

TEST(MltRanks, AStepOverRanksRunsManyIterationsAndEndsTheBudgetAsOneProcess) {
    const Scene scene = causticScene();
    const RankRig rig(scene, mltRequest("64"));  // 64 chains on 16 x 12 pixels: 1/3 mutation per pixel each
    rig.run(2, [&](IntegratorSession& session, Communicator&) {
        session.step(0);
        session.step(0);  // no budget: 2^16 proposals in all
        EXPECT_EQ(statOf(session, "mlt_iterations"), "1024");
        session.step(0.5);  // half a mutation per pixel left: 2 iterations reach it, as in one process
        EXPECT_EQ(statOf(session, "mlt_iterations"), "1026");
        EXPECT_NEAR(session.samplesPerPixel(), 1026.0 / 3.0, 1e-9);
    });
}

TEST(MltRanks, FewerChainsThanRanksAreRefused) {
    const Scene scene = causticScene();
    const RankRig rig(scene, mltRequest("2"));
    try {
        rig.run(3, [](IntegratorSession&, Communicator&) {});
        FAIL() << "2 chains over 3 ranks were accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("2 chains cannot be split over 3 ranks"), std::string::npos) << e.what();
    }
}

TEST(MltRanks, BytesSentAreReported) {
    const Scene scene = causticScene();
    const RankRig rig(scene, mltRequest("16"));
    rig.run(2, [&](IntegratorSession& session, Communicator&) {
        session.step(0);
        session.step(kOneIteration);
        session.step(kOneIteration);
        session.develop();
        // InProcessGroup counts the bytes a rank contributes: nothing in an iteration, its half of
        // the 4096 bootstrap samples (luminance and pixel, 4 bytes each); a develop sends its film
        // (6 doubles a pixel) and the counters of the 2 iterations since the last meeting (accepted,
        // large steps, one importance sum per iteration: 4 doubles).
        EXPECT_EQ(std::stod(statOf(session, "bytes_sent_per_iteration")), 0);
        EXPECT_EQ(std::stoull(statOf(session, "mlt_bootstrap_bytes_sent")), 2048u * 8u);
        EXPECT_EQ(std::stoull(statOf(session, "mlt_develop_bytes_sent")), 16u * 12u * 6u * 8u + 4u * 8u);
        EXPECT_EQ(std::stoull(statOf(session, "bytes_sent")), 2048u * 8u + 16u * 12u * 6u * 8u + 4u * 8u);
    });
}

}  // namespace
}  // namespace caustica::test
