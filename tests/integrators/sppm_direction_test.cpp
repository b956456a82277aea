// sppm_direction_test.cpp — direction "auto" (sppm_direction.h): a fixed direction never changes;
// auto gathers without timing anything when the pilot finds many photons per visible point, and
// otherwise alternates gather and deposit passes and keeps the one whose second pass was faster
// (the first of each is a warm-up and not compared).
#include <gtest/gtest.h>

#include <string>

#include "caustica/integrators/sppm/sppm_direction.h"

namespace caustica::test {
namespace {

TEST(SppmDirection, AFixedDirectionIsNeverTimed) {
    for (PhotonDirection d : {PhotonDirection::Gather, PhotonDirection::Deposit}) {
        SppmDirectionChooser c(d);
        EXPECT_FALSE(c.needsPilot());
        EXPECT_TRUE(c.decided());
        for (double seconds : {5.0, 0.1, 9.0}) {
            EXPECT_EQ(c.next(), d);
            c.passed(seconds);
        }
        EXPECT_EQ(c.current(), d);
        EXPECT_EQ(c.describe(), photonDirectionName(d));
    }
}

TEST(SppmDirection, ManyPhotonsPerVisiblePointGatherWithoutTiming) {
    SppmDirectionChooser c(PhotonDirection::Auto);
    EXPECT_TRUE(c.needsPilot());
    EXPECT_EQ(c.current(), PhotonDirection::Auto);
    c.pilot(kSppmGatherWithoutTrial * 1000, 1000);  // exactly at the threshold
    EXPECT_FALSE(c.needsPilot());
    EXPECT_TRUE(c.decided());
    EXPECT_EQ(c.next(), PhotonDirection::Gather);
    c.passed(100.0);  // a slow pass changes nothing once decided
    EXPECT_EQ(c.next(), PhotonDirection::Gather);
    EXPECT_NE(c.describe().find("gather (auto: 0.25 photons stored per visible point"), std::string::npos)
        << c.describe();
}

/// Auto with few photons per visible point, passes taking `seconds` in turn; returns the choice.
PhotonDirection chooseAfterTiming(const double (&seconds)[4], std::string* description = nullptr) {
    SppmDirectionChooser c(PhotonDirection::Auto);
    c.pilot(100, 1000);
    const PhotonDirection expected[4] = {PhotonDirection::Gather, PhotonDirection::Deposit, PhotonDirection::Gather,
                                         PhotonDirection::Deposit};
    for (int i = 0; i < 4; ++i) {
        EXPECT_FALSE(c.decided()) << "pass " << i;
        EXPECT_EQ(c.current(), PhotonDirection::Auto);
        EXPECT_EQ(c.next(), expected[i]) << "pass " << i;
        c.passed(seconds[i]);
    }
    EXPECT_TRUE(c.decided());
    if (description) *description = c.describe();
    return c.next();
}

TEST(SppmDirection, FewPhotonsPerVisiblePointKeepTheFasterSecondPass) {
    std::string text;
    // Deposit's first pass slow (first-touch page faults), its second the faster: deposit.
    EXPECT_EQ(chooseAfterTiming({0.05, 0.09, 0.05, 0.04}, &text), PhotonDirection::Deposit);
    EXPECT_EQ(text, "deposit (auto: 0.1 photons stored per visible point; passes timed: gather 0.05 s, deposit 0.04 s)");
    // Gather's first pass slow, its second the faster: gather.
    EXPECT_EQ(chooseAfterTiming({0.09, 0.05, 0.03, 0.04}), PhotonDirection::Gather);
    // First passes would say the opposite of the second ones.
    EXPECT_EQ(chooseAfterTiming({0.01, 0.05, 0.06, 0.05}), PhotonDirection::Deposit);
    // A tie keeps gather.
    EXPECT_EQ(chooseAfterTiming({0.05, 0.05, 0.05, 0.05}), PhotonDirection::Gather);
}

TEST(SppmDirection, NoVisiblePointsStillDecide) {
    SppmDirectionChooser c(PhotonDirection::Auto);
    c.pilot(0, 0);
    EXPECT_EQ(c.next(), PhotonDirection::Gather);
    for (double s : {1.0, 2.0, 1.0, 2.0}) c.passed(s);
    EXPECT_TRUE(c.decided());
    EXPECT_EQ(c.next(), PhotonDirection::Gather);
}

}  // namespace
}  // namespace caustica::test
