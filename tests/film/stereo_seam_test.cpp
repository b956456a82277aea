// stereo_seam_test.cpp — a stereo film (two eyes side by side, film/eye_seam.h) never lets the
// reconstruction filter cross the seam: each eye develops exactly as a mono film of its width
// fed the same samples (the seam normalised as a border), and MLT's atomic splats stay in their eye.
#include <gtest/gtest.h>

#include <vector>

#include "caustica/film/film.h"
#include "caustica/integrators/mlt/mlt_splat.h"
#include "caustica/util/rng.h"

namespace caustica {
namespace {

constexpr int kW = 9, kH = 5, kK = 3;

/// Random positions in their pixels; radiance 1 in the left eye, 0 in the right eye, plus noise.
SamplePass stereoPass(uint64_t seed) {
    SamplePass pass(2 * kW, kH, kK);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < 2 * kW; ++x)
            for (int k = 0; k < kK; ++k) {
                IndependentSampler s(uint64_t(y * 2 * kW + x), uint64_t(k), seed);
                const Vec2f j = s.get2D();
                const Float v = x < kW ? 1.0f + 0.5f * s.get1D() : 0.0f;
                pass.at(x, y, k) = PixelSample{Vec2f(Float(x) + j.x, Float(y) + j.y), Spectrum(v, v, 2 * v)};
            }
    return pass;
}

SamplePass eyePass(const SamplePass& stereo, int eye) {
    SamplePass pass(kW, kH, kK);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int k = 0; k < kK; ++k) {
                PixelSample s = stereo.at(x + eye * kW, y, k);
                s.pos.x -= Float(eye * kW);
                pass.at(x, y, k) = s;
            }
    return pass;
}

TEST(StereoSeam, EachEyeDevelopsAsAMonoFilmOfItsWidth) {
    for (const Filter& filter : {Filter::gaussian(), Filter::gaussian(1.0f), Filter::tent(1.5f)}) {
        Film stereo(2 * kW, kH, filter);
        stereo.setEyeWidth(kW);
        Film mono[2] = {Film(kW, kH, filter), Film(kW, kH, filter)};
        for (uint64_t pass = 0; pass < 2; ++pass) {
            const SamplePass p = stereoPass(pass + 11);
            stereo.addPass(p);
            for (int eye = 0; eye < 2; ++eye) mono[eye].addPass(eyePass(p, eye));
        }
        const Image s = stereo.develop();
        for (int eye = 0; eye < 2; ++eye) {
            const Image m = mono[eye].develop();
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    for (int c = 0; c < 3; ++c) ASSERT_EQ(s.pixel(x + eye * kW, y)[c], m.pixel(x, y)[c]);
        }
        // The right eye is black up to the seam: nothing of the bright left eye leaked across.
        for (int y = 0; y < kH; ++y) EXPECT_EQ(s.pixel(kW, y)[0], 0.0f);
    }
}

TEST(StereoSeam, FilmRefusesAnEyeWidthThatIsNotHalfItsWidth) {
    Film film(2 * kW, kH, Filter::box());
    EXPECT_THROW(film.setEyeWidth(kW + 1), Error);
    FilmDesc desc;
    desc.width = 2 * kW;
    desc.height = kH;
    desc.eyeWidth = kW;
    EXPECT_EQ(Film(desc).eyeWidth(), kW);
}

TEST(StereoSeam, MltSplatsStayInTheirEye) {
    std::vector<float> accum(size_t(2 * kW * kH) * kMltValuesPerPixel, 0.0f);
    const MltSplat splats[2] = {{Vec2f(Float(kW) - 0.1f, 2.5f), Spectrum(1), Spectrum(0)},   // left, at the seam
                                {Vec2f(Float(kW) + 0.1f, 2.5f), Spectrum(2), Spectrum(0)}};  // right, at the seam
    MltSplatView v;
    v.width = 2 * kW;
    v.height = kH;
    v.filter = Filter::gaussian(1.0f);
    v.footprint = v.filter.footprint();
    v.splats = splats;
    v.count = 2;
    v.accum = accum.data();
    // Sum of the first channel over the columns [x0, x1) after splatting splat i.
    auto columns = [&](uint32_t i, int eyeWidth, int x0, int x1) {
        std::fill(accum.begin(), accum.end(), 0.0f);
        v.eyeWidth = eyeWidth;
        splatAtomic(v, i);
        float sum = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = x0; x < x1; ++x) sum += accum[size_t(y * 2 * kW + x) * kMltValuesPerPixel];
        return sum;
    };
    EXPECT_EQ(columns(0, kW, kW, 2 * kW), 0.0f);  // the left splat never reaches the right eye
    EXPECT_GT(columns(0, kW, 0, kW), 0.0f);
    EXPECT_EQ(columns(1, kW, 0, kW), 0.0f);       // nor the right splat the left eye
    EXPECT_GT(columns(1, kW, kW, 2 * kW), 0.0f);
    EXPECT_GT(columns(0, 0, kW, 2 * kW), 0.0f);   // without the seam they would
    EXPECT_GT(columns(1, 0, 0, kW), 0.0f);
}

}  // namespace
}  // namespace caustica
