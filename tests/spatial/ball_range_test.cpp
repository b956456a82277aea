// ball_range_test.cpp — forEachInBallRange (the uniform grid's blocked distance test) reports
// exactly the positions of a range that inBall accepts, once each, in ascending order, for ranges
// of every length around the block size and at every offset (full blocks, partial tails, empty).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "caustica/spatial/ball_range.h"

namespace caustica::test {
namespace {

TEST(BallRange, ReportsWhatInBallAcceptsInOrder) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<Vec3f> positions(64);
    for (Vec3f& p : positions) p = Vec3f(u(rng), u(rng), u(rng));
    positions[5] = Vec3f(0.5f, 0, 0);  // exactly on the sphere: the closed ball keeps it
    const Vec3f center(0, 0, 0);
    const Float radius = 0.5f;
    size_t inside = 0;
    for (uint32_t begin = 0; begin < 12; ++begin)
        for (uint32_t end = begin; end <= begin + 3 * kBallBlock + 1 && end <= positions.size(); ++end) {
            std::vector<uint32_t> expected, found;
            for (uint32_t k = begin; k < end; ++k)
                if (inBall(positions[k], center, radius)) expected.push_back(k);
            const auto report = [&](uint32_t k) { found.push_back(k); };
            forEachInBallRange(positions.data(), begin, end, center, radius, report);
            EXPECT_EQ(found, expected) << "range [" << begin << ", " << end << ")";
            inside += expected.size();
        }
    EXPECT_GT(inside, 0u);  // the ranges hold points inside and outside the ball
}

}  // namespace
}  // namespace caustica::test
