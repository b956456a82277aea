// film_test.cpp — the deterministic gathering film: reconstruction, determinism across thread
// counts, invalid samples, checkpoints.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>

#include "caustica/film/film.h"
#include "film/random_pass.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

using test::randomPass;

bool bitIdentical(const Image& a, const Image& b) {
    return a.sameSize(b) && std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * 4) == 0;
}

TEST(Film, BoxFilterOneSampleReproducesSamples) {
    Film film(7, 5, Filter::box());
    const SamplePass pass = randomPass(7, 5, 1, 1);
    film.addPass(pass);
    const Image img = film.develop();
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(img.at(x, y)[c], pass.at(x, y, 0).L[c]) << x << "," << y;
    EXPECT_EQ(film.samplesPerPixel(), 1u);
    EXPECT_EQ(film.invalidSamples(), 0u);
}

TEST(Film, BoxFilterAveragesOwnPixelAcrossPasses) {
    Film film(4, 3, Filter::box());
    const SamplePass a = randomPass(4, 3, 3, 2), b = randomPass(4, 3, 2, 3);
    film.addPass(a);
    film.addPass(b);
    const Image img = film.develop();
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            Spectrum sum;
            for (int k = 0; k < 3; ++k) sum += a.at(x, y, k).L;
            for (int k = 0; k < 2; ++k) sum += b.at(x, y, k).L;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y)[c], sum[c] / 5, 1e-5);
        }
    EXPECT_EQ(film.samplesPerPixel(), 5u);
}

TEST(Film, TentFilterHandComputed) {
    // Pixel 0: sample at its centre (L = 1); pixel 1: 0.75 right of pixel 0's centre (L = 3).
    // out0 = (1 * 1 + 0.25 * 3) / 1.25 = 1.4, out1 = (0.75 * 3) / 0.75 = 3.
    Film film(2, 1, Filter::tent());
    SamplePass pass(2, 1, 1);
    pass.at(0, 0, 0) = {Vec2f(0.5f, 0.5f), Spectrum(1.0f)};
    pass.at(1, 0, 0) = {Vec2f(1.25f, 0.5f), Spectrum(3.0f)};
    film.addPass(pass);
    const Image img = film.develop();
    EXPECT_FLOAT_EQ(img.at(0, 0).r, 1.4f);
    EXPECT_FLOAT_EQ(img.at(1, 0).g, 3.0f);
}

TEST(Film, ConstantRadianceDevelopsToConstantEverywhere) {
    for (const Filter& filter : {Filter::gaussian(), Filter::gaussian(1.0f), Filter::tent()}) {
        Film film(9, 6, filter);
        SamplePass pass = randomPass(9, 6, 4, 4);
        for (PixelSample& s : pass.samples) s.L = Spectrum(0.7f, 2.5f, 1e-3f);
        film.addPass(pass);
        const Image img = film.develop();
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 9; ++x) {  // includes the borders and corners
                EXPECT_NEAR(img.at(x, y).r, 0.7f, 1e-6);
                EXPECT_NEAR(img.at(x, y).g, 2.5f, 3e-6);
                EXPECT_NEAR(img.at(x, y).b, 1e-3f, 1e-9);
            }
    }
}

TEST(Film, BitIdenticalForDifferentThreadCounts) {
    auto render = [](int threads) {
        Film film(61, 37, Filter::gaussian());
        tbb::task_arena arena(threads);
        arena.execute([&] {
            for (uint32_t p = 0; p < 3; ++p) film.addPass(randomPass(61, 37, 4, 100 + p));
        });
        return film;
    };
    const Film one = render(1), two = render(2), four = render(4);
    const Image a = one.develop(), b = two.develop(), c = four.develop();
    EXPECT_TRUE(bitIdentical(a, b));
    EXPECT_TRUE(bitIdentical(a, c));
    EXPECT_EQ(
        std::memcmp(one.sums().data(), two.sums().data(), one.sums().size() * sizeof(FilmPixel)),
        0);
}

TEST(Film, InvalidSamplesAreCountedAndDropped) {
    Film film(3, 2, Filter::box());
    SamplePass pass = randomPass(3, 2, 2, 5);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    pass.at(0, 0, 0).L = Spectrum(nan, 1, 1);
    pass.at(1, 0, 1).L = Spectrum(1, inf, 1);
    pass.at(2, 0, 0).L = Spectrum(1, 1, -0.5f);
    pass.at(0, 1, 0).pos = Vec2f(2.5f, 1.5f);  // in pixel (2, 1), stored for pixel (0, 1)
    pass.at(1, 1, 0).pos = Vec2f(nan, 1.5f);
    pass.at(1, 1, 1).L = Spectrum(-inf, 0, 0);  // pixel (1, 1): both samples invalid
    film.addPass(pass);
    EXPECT_EQ(film.invalidSamples(), 6u);
    const Image img = film.develop();
    EXPECT_TRUE(img.allFinite());
    // Each affected pixel shows exactly its remaining valid sample; pixel (1, 1) none: black.
    EXPECT_EQ(img.at(0, 0).r, pass.at(0, 0, 1).L.r);
    EXPECT_EQ(img.at(1, 0).g, pass.at(1, 0, 0).L.g);
    EXPECT_EQ(img.at(2, 0).b, pass.at(2, 0, 1).L.b);
    EXPECT_EQ(img.at(0, 1).r, pass.at(0, 1, 1).L.r);
    EXPECT_EQ(img.at(1, 1).r, 0.0f);
    EXPECT_EQ(img.at(2, 1).r, 0.5f * (pass.at(2, 1, 0).L.r + pass.at(2, 1, 1).L.r));
}

// The box filter's one-kernel path (film_gather.h, GatherGrid::box) forms the general two-kernel
// path's sums and invalid counts bit for bit, invalid samples of every kind included.
TEST(Film, BoxFilterShortPathEqualsTheGeneralGather) {
    const int w = 9, h = 7, k = 5;
    SamplePass pass = randomPass(w, h, k, 11);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    pass.at(0, 0, 0).L = Spectrum(nan, 1, 1);
    pass.at(3, 2, 4).L = Spectrum(1, -1, 1);
    pass.at(4, 4, 1).pos = Vec2f(6.5f, 4.5f);  // in another pixel
    pass.at(8, 6, 2).pos = Vec2f(8.0f - 0.01f, 6.5f);  // within the slack: kept
    pass.at(5, 1, 0).pos = Vec2f(5.5f, nan);
    std::vector<float> weightsShort, weightsGeneral;
    std::vector<uint32_t> invalidShort, invalidGeneral;
    FilmSplatView shortView, generalView;
    shortView.samples = generalView.samples = pass.samples.data();
    shortView.grid = gatherGrid(w, h, k, Filter::box(), weightsShort, invalidShort);
    ASSERT_TRUE(shortView.grid.box);
    EXPECT_TRUE(weightsShort.empty());
    generalView.grid = gatherGrid(w, h, k, Filter::box(), weightsGeneral, invalidGeneral);
    generalView.grid.box = false;
    weightsGeneral.resize(size_t(w) * h * k * 2);
    generalView.grid.weights = weightsGeneral.data();
    for (size_t pixel = 0; pixel < size_t(w) * h; ++pixel) {
        sampleWeights(shortView, pixel);
        sampleWeights(generalView, pixel);
    }
    for (size_t pixel = 0; pixel < size_t(w) * h; ++pixel) {
        float a[3], aw, b[3], bw;
        gatherSums<3>(shortView.grid, shortView, pixel, a, aw);
        gatherSums<3>(generalView.grid, generalView, pixel, b, bw);
        EXPECT_EQ(std::memcmp(a, b, sizeof a), 0) << pixel;
        EXPECT_EQ(std::memcmp(&aw, &bw, sizeof aw), 0) << pixel;
        EXPECT_EQ(invalidShort[pixel], invalidGeneral[pixel]) << pixel;
    }
    EXPECT_EQ(std::accumulate(invalidShort.begin(), invalidShort.end(), 0u), 4u);
}

TEST(Film, SamplesOnThePixelEdgeAreKept) {
    // A position rounded up to the next pixel's edge is clamped into its own pixel.
    Film film(2, 2, Filter::box());
    SamplePass pass(2, 2, 1);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) pass.at(x, y, 0) = {Vec2f(x + 1.0f, y + 1.0f), Spectrum(1.0f)};
    film.addPass(pass);
    EXPECT_EQ(film.invalidSamples(), 0u);
    const Image img = film.develop();
    for (float v : img.rgb) EXPECT_EQ(v, 1.0f);
}

TEST(Film, RejectsMismatchedPass) {
    Film film(4, 4, Filter::box());
    EXPECT_THROW(film.addPass(SamplePass(4, 5, 1)), Error);
    SamplePass bad(4, 4, 2);
    bad.samples.pop_back();
    EXPECT_THROW(film.addPass(bad), Error);
    EXPECT_THROW(Film(0, 4, Filter::box()), Error);
}

TEST(Film, ResetForgetsEverything) {
    Film film(3, 3, Filter::gaussian());
    film.addPass(randomPass(3, 3, 2, 6));
    film.reset();
    EXPECT_EQ(film.samplesPerPixel(), 0u);
    for (float v : film.develop().rgb) EXPECT_EQ(v, 0.0f);
}

TEST(Film, MergeEqualsAccumulatingBothPasses) {
    const SamplePass a = randomPass(8, 8, 2, 7), b = randomPass(8, 8, 3, 8);
    Film both(8, 8, Filter::tent()), first(8, 8, Filter::tent()), second(8, 8, Filter::tent());
    both.addPass(a);
    both.addPass(b);
    first.addPass(a);
    second.addPass(b);
    first.merge(second);
    EXPECT_TRUE(bitIdentical(both.develop(), first.develop()));
    EXPECT_EQ(first.samplesPerPixel(), 5u);
    EXPECT_THROW(first.merge(Film(8, 8, Filter::box())), Error);
}

TEST(Film, CheckpointRoundTrip) {
    Film film(13, 7, Filter::gaussian());
    SamplePass pass = randomPass(13, 7, 3, 9);
    pass.at(2, 2, 1).L.r = -1.0f;
    film.addPass(pass);
    std::stringstream stream;
    film.save(stream);

    Film restored(13, 7, Filter::gaussian());
    restored.load(stream);
    EXPECT_EQ(restored.samplesPerPixel(), 3u);
    EXPECT_EQ(restored.invalidSamples(), 1u);
    EXPECT_TRUE(bitIdentical(film.develop(), restored.develop()));
    // Resuming gives exactly what an uninterrupted render gives.
    const SamplePass next = randomPass(13, 7, 3, 10);
    film.addPass(next);
    restored.addPass(next);
    EXPECT_TRUE(bitIdentical(film.develop(), restored.develop()));
}

TEST(Film, CheckpointRefusesMismatchAndCorruption) {
    Film film(6, 4, Filter::gaussian());
    film.addPass(randomPass(6, 4, 1, 11));
    std::stringstream stream;
    film.save(stream);
    const std::string bytes = stream.str();

    auto loadInto = [](Film& f, const std::string& data) {
        std::istringstream in(data);
        f.load(in);
    };
    Film wrongSize(4, 6, Filter::gaussian());
    EXPECT_THROW(loadInto(wrongSize, bytes), Error);
    EXPECT_EQ(wrongSize.samplesPerPixel(), 0u);  // unchanged
    Film wrongFilter(6, 4, Filter::box());
    EXPECT_THROW(loadInto(wrongFilter, bytes), Error);

    Film target(6, 4, Filter::gaussian());
    target.addPass(randomPass(6, 4, 2, 12));
    const Image before = target.develop();
    EXPECT_THROW(loadInto(target, bytes.substr(0, bytes.size() - 9)), Error);  // truncated
    std::string corrupt = bytes;
    corrupt[bytes.size() / 2] ^= 0x10;
    EXPECT_THROW(loadInto(target, corrupt), Error);
    std::string badMagic = bytes;
    badMagic[0] = 'X';
    EXPECT_THROW(loadInto(target, badMagic), Error);
    EXPECT_THROW(loadInto(target, ""), Error);
    EXPECT_TRUE(bitIdentical(before, target.develop()));  // failed loads changed nothing
    EXPECT_EQ(target.samplesPerPixel(), 2u);
    loadInto(target, bytes);
    EXPECT_TRUE(bitIdentical(film.develop(), target.develop()));
}

}  // namespace
}  // namespace caustica
