// aov_film_test.cpp — the aovs list (Mitsuba's names and channels, errors), the N-channel AovFilm
// (the RGB Film's gather, thread-count independence, checkpoints) and the per-pixel variance
// against a hand-computed sample variance.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <sstream>

#include "caustica/film/aov_film.h"
#include "caustica/film/aov_layers.h"
#include "caustica/film/film.h"
#include "caustica/film/pixel_variance.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"

namespace caustica::test {
namespace {

TEST(AovSpec, ParsesMitsubasListWithItsChannelNames) {
    const AovSpec spec = parseAovSpec(
        "dd.y:depth, "
        "nn:sh_normal,ng:geo_normal,p:position,uv:uv,a:albedo,pi:prim_index,si:shape_index,v:"
        "variance",
        "--aov");
    ASSERT_EQ(spec.layers.size(), 9u);
    EXPECT_EQ(spec.text(),
              "dd.y:depth,nn:sh_normal,ng:geo_normal,p:position,uv:uv,a:albedo,pi:prim_index,si:"
              "shape_index,v:variance");
    const std::vector<std::string> expected = {
        "dd.y.T", "nn.X", "nn.Y", "nn.Z", "ng.X", "ng.Y", "ng.Z", "p.X", "p.Y", "p.Z",
        "uv.U",   "uv.V", "a.R",  "a.G",  "a.B",  "pi.I", "si.I", "v.R", "v.G", "v.B"};
    EXPECT_EQ(spec.channelNames(), expected);
    EXPECT_TRUE(spec.has(AovType::Variance));
    EXPECT_FALSE(parseAovSpec("d:depth", "x").has(AovType::Albedo));
}

TEST(AovSpec, RefusesMalformedListsNamingWhere) {
    const std::pair<const char*, const char*> bad[] = {
        {"", "is empty"},
        {"dd.y:depth,", "not a NAME:TYPE pair"},
        {"depth", "not a NAME:TYPE pair"},
        {":depth", "not a NAME:TYPE pair"},
        {"a:b:depth", "not a NAME:TYPE pair"},
        {"d:dept", "unknown AOV type 'dept'"},
        {"d:depth,d:uv", "given twice"},
        {"R:depth", "taken by the image's own channels"},
    };
    for (const auto& [text, reason] : bad) {
        try {
            parseAovSpec(text, "scene.xml:3");
            ADD_FAILURE() << "accepted '" << text << "'";
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind("scene.xml:3: ", 0), 0u) << msg;
            EXPECT_NE(msg.find(reason), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

/// A pass of random samples (positions inside their pixels) for both films.
void randomPasses(int w, int h, int k, SamplePass& rgb, AovSamplePass& aov) {
    rgb = SamplePass(w, h, k);
    aov = AovSamplePass(w, h, k, 3);
    for (size_t pixel = 0; pixel < size_t(w * h); ++pixel)
        for (int s = 0; s < k; ++s) {
            IndependentSampler rng(pixel, uint64_t(s), 5);
            const size_t slot = pixel * size_t(k) + size_t(s);
            const Vec2f jitter = rng.get2D();
            const Vec2f pos(Float(pixel % size_t(w)) + jitter.x,
                            Float(pixel / size_t(w)) + jitter.y);
            const Spectrum L(rng.get1D() * 4, rng.get1D(), rng.get1D() * 0.5f);
            rgb.samples[slot] = PixelSample{pos, L};
            aov.positions[slot] = pos;
            for (int c = 0; c < 3; ++c) aov.values[slot * 3 + size_t(c)] = L[c];
        }
}

// The AovFilm's gather is the Film's, generalised: the same samples develop to the same bits.
TEST(AovFilm, DevelopsExactlyAsTheRgbFilm) {
    const Filter gaussian = Filter::fromDesc(FilterDesc{});
    SamplePass rgb;
    AovSamplePass aov;
    randomPasses(9, 7, 3, rgb, aov);
    Film film(9, 7, gaussian);
    AovFilm aovFilm(9, 7, gaussian, 3);
    film.addPass(rgb);
    aovFilm.addPass(aov);
    film.addPass(rgb);
    aovFilm.addPass(aov);
    const Image image = film.develop();
    const std::vector<float> values = aovFilm.develop();
    ASSERT_EQ(values.size(), image.rgb.size());
    EXPECT_TRUE(values == image.rgb);
    EXPECT_EQ(aovFilm.samplesPerPixel(), 6u);
}

TEST(AovFilm, SameBitsForOneAndTwoThreadsAndManyChannels) {
    const int w = 23, h = 17, k = 2, C = 6;
    AovSamplePass pass(w, h, k, C);
    for (size_t slot = 0; slot < pass.slots(); ++slot) {
        IndependentSampler rng(slot, 0, 9);
        const size_t pixel = slot / size_t(k);
        const Vec2f j = rng.get2D();
        pass.positions[slot] =
            Vec2f(Float(pixel % size_t(w)) + j.x, Float(pixel / size_t(w)) + j.y);
        for (int c = 0; c < C; ++c)
            pass.values[slot * C + size_t(c)] = rng.get1D() - 0.5f;  // negative too
    }
    pass.values[5] = std::nanf("");  // drops slot 0 from every channel
    auto develop = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        AovFilm film(w, h, Filter::fromDesc(FilterDesc{}), C);
        film.addPass(pass);
        return film.develop();
    };
    const std::vector<float> one = develop(1), two = develop(2);
    EXPECT_TRUE(one == two);
    for (float v : one) EXPECT_TRUE(std::isfinite(v));
}

TEST(AovFilm, CheckpointRoundTripAndRefusals) {
    const Filter box = Filter::fromDesc(FilterDesc{FilterType::Box, 0.5f, 0.5f});
    AovSamplePass pass(4, 3, 2, 5);
    for (size_t slot = 0; slot < pass.slots(); ++slot) {
        const size_t pixel = slot / 2;
        pass.positions[slot] = Vec2f(Float(pixel % 4) + 0.25f, Float(pixel / 4) + 0.75f);
        for (int c = 0; c < 5; ++c) pass.values[slot * 5 + size_t(c)] = Float(slot) + Float(c);
    }
    AovFilm film(4, 3, box, 5);
    film.addPass(pass);
    std::stringstream ckpt;
    film.save(ckpt);
    AovFilm restored(4, 3, box, 5);
    restored.load(ckpt);
    EXPECT_TRUE(restored.develop() == film.develop());
    EXPECT_EQ(restored.samplesPerPixel(), 2u);
    // Box filter: the plain mean of the pixel's two samples.
    EXPECT_FLOAT_EQ(film.develop()[0], 0.5f);
    AovFilm otherChannels(4, 3, box, 4);
    std::stringstream again(ckpt.str());
    EXPECT_THROW(otherChannels.load(again), Error);
    std::string damaged = ckpt.str();
    damaged[60] ^= 1;
    std::stringstream bad(damaged);
    EXPECT_THROW(restored.load(bad), Error);
}

// Variance of the pixel mean, s² / n, against the sums done by hand.
TEST(PixelVariance, MatchesTheHandComputedSampleVariance) {
    SamplePass pass(2, 1, 4);
    const float values[2][4] = {{1, 2, 4, 7}, {3, 3, 3, 3}};
    for (int x = 0; x < 2; ++x)
        for (int k = 0; k < 4; ++k)
            pass.at(x, 0, k) = PixelSample{Vec2f(Float(x) + 0.5f, 0.5f),
                                           Spectrum(values[x][k], 0, 2 * values[x][k])};
    PixelVariance variance(2, 1);
    variance.addPass(pass);
    std::vector<float> v = variance.develop();
    // Pixel 0: mean 3.5, s² = ((2.5² + 1.5² + 0.5² + 3.5²) / 3) = 7, variance of the mean 7 / 4.
    EXPECT_FLOAT_EQ(v[0], 1.75f);
    EXPECT_FLOAT_EQ(v[1], 0.0f);
    EXPECT_FLOAT_EQ(v[2], 7.0f);  // 2x the values: 4x the variance
    EXPECT_FLOAT_EQ(v[3], 0.0f);  // a constant pixel
    // A second pass adds samples: 8 samples, 1 2 4 7 1 2 4 7: s² = 6 (sum of squares 42 / 7), / 8.
    variance.addPass(pass);
    v = variance.develop();
    EXPECT_FLOAT_EQ(v[0], 0.75f);
    // Invalid samples (NaN, outside the pixel) are left out, as the film drops them.
    pass.at(0, 0, 3).L = Spectrum(std::nanf(""), 0, 0);
    pass.at(0, 0, 2).pos = Vec2f(1.5f, 0.5f);
    PixelVariance two(2, 1);
    two.addPass(pass);
    EXPECT_FLOAT_EQ(two.develop()[0], 0.25f);  // samples 1, 2: s² = 0.5, / 2
    std::stringstream ckpt;
    two.save(ckpt);
    PixelVariance restored(2, 1);
    restored.load(ckpt);
    EXPECT_TRUE(restored.develop() == two.develop());
}

}  // namespace
}  // namespace caustica::test
