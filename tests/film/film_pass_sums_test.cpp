// Film::passSums / addPassSums (the pass exchange of MPI ranks, render/pass_session.cpp): adding
// a pass's sums leaves the film with the bits addPass leaves, invalid samples counted alike.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "caustica/film/film.h"
#include "film/random_pass.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

using test::randomPass;

TEST(FilmPassSums, AddingAPasssSumsLeavesTheBitsOfAddPass) {
    for (const Filter& filter : {Filter::box(), Filter::gaussian(), Filter::tent()}) {
        Film direct(9, 6, filter), viaSums(9, 6, filter), other(9, 6, filter);
        for (uint32_t seed = 1; seed <= 3; ++seed) {
            SamplePass pass = randomPass(9, 6, int(seed) + 1, seed);
            pass.at(2, 3, 0).L.r = std::numeric_limits<float>::quiet_NaN();  // counted and dropped
            direct.addPass(pass);
            uint64_t invalid = 0;
            // Filtered by another film (another rank's), added to this one.
            const std::vector<PassPixelSums> sums = other.passSums(pass, invalid);
            EXPECT_EQ(invalid, 1u);
            viaSums.addPassSums(sums, pass.samplesPerPixel, invalid);
        }
        EXPECT_EQ(other.samplesPerPixel(), 0u);  // passSums leaves its film alone
        EXPECT_EQ(viaSums.samplesPerPixel(), direct.samplesPerPixel());
        EXPECT_EQ(viaSums.invalidSamples(), direct.invalidSamples());
        ASSERT_EQ(viaSums.sums().size(), direct.sums().size());
        EXPECT_EQ(std::memcmp(viaSums.sums().data(), direct.sums().data(), direct.sums().size() * sizeof(FilmPixel)),
                  0);
    }
}

TEST(FilmPassSums, SumsOfAnotherSizeAreRefused) {
    Film film(4, 3, Filter::box());
    EXPECT_THROW(film.addPassSums(std::vector<PassPixelSums>(11), 1, 0), Error);
    uint64_t invalid = 0;
    EXPECT_THROW(film.passSums(randomPass(3, 3, 1, 1), invalid), Error);
}

}  // namespace
}  // namespace caustica
