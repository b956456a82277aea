// tonemap_test.cpp — the ldrfilm tone mapping (film/tonemap.h): the gamma method with exposure and
// gamma, Reinhard's operator against its formula, and PNG levels that survive the sRGB encoder.
#include <gtest/gtest.h>

#include <cmath>

#include "caustica/film/tonemap.h"

namespace caustica {
namespace {

TEST(ToneMap, GammaExposureAndSrgb) {
    Image img(3, 1);
    img.set(0, 0, Spectrum(0.1f, 0.25f, 2.0f));
    img.set(1, 0, Spectrum(0.0f, -1.0f, 0.5f));
    img.set(2, 0, Spectrum(0.001f));
    ToneMapDesc t;
    t.ldr = true;
    Image srgb = toneMap(img, t);
    EXPECT_FLOAT_EQ(srgb.at(0, 0).r, linearToSrgb(0.1f));
    EXPECT_FLOAT_EQ(srgb.at(0, 0).b, 1.0f);  // clamped
    EXPECT_FLOAT_EQ(srgb.at(1, 0).g, 0.0f);
    t.exposure = 1;  // x 2
    t.gamma = 2.2f;
    Image g = toneMap(img, t);
    EXPECT_NEAR(g.at(0, 0).r, std::pow(0.2, 1 / 2.2), 1e-6);
    EXPECT_NEAR(g.at(0, 0).g, std::pow(0.5, 1 / 2.2), 1e-6);
    EXPECT_NEAR(g.at(2, 0).r, std::pow(0.002, 1 / 2.2), 1e-6);
}

TEST(ToneMap, ReinhardFollowsItsFormula) {
    Image img(2, 1);
    img.set(0, 0, Spectrum(0.2f, 0.4f, 0.1f));
    img.set(1, 0, Spectrum(4.0f, 3.0f, 2.0f));
    ToneMapDesc t;
    t.method = ToneMapMethod::Reinhard;
    t.gamma = 1;  // linear output: the operator alone
    t.key = 0.3f;
    t.burn = 0.25f;
    const Image out = toneMap(img, t);
    const double y0 = img.at(0, 0).luminance(), y1 = img.at(1, 0).luminance();
    const double logAvg = std::exp(0.5 * (std::log(1e-3 + y0) + std::log(1e-3 + y1)));
    const double scale = 0.3 / logAvg, white = y1 * scale, b = 0.75;
    for (int x = 0; x < 2; ++x) {
        const double y = x ? y1 : y0, l = y * scale;
        const double ld = l * (1 + l / (white * white * b * b * b * b)) / (1 + l);
        const Spectrum c = img.at(x, 0);
        EXPECT_NEAR(out.at(x, 0).r, std::min(1.0, c.r * ld / y), 1e-5) << x;
        EXPECT_NEAR(out.at(x, 0).g, std::min(1.0, c.g * ld / y), 1e-5) << x;
        EXPECT_NEAR(out.at(x, 0).b, std::min(1.0, c.b * ld / y), 1e-5) << x;
    }
}

/// image_io's PNG writer stores lround(linearToSrgb(v) · 255): every display level k / 255 must
/// come back as k after displayToPngLinear.
TEST(ToneMap, DisplayLevelsSurviveThePngEncoder) {
    Image display(256, 1);
    for (int k = 0; k < 256; ++k) display.set(k, 0, Spectrum(k / 255.0f, (k + 0.4f) / 255.0f, 1.0f));
    const Image linear = displayToPngLinear(display);
    for (int k = 0; k < 256; ++k) {
        EXPECT_EQ(std::lround(linearToSrgb(linear.at(k, 0).r) * 255.0f), k);
        EXPECT_EQ(std::lround(linearToSrgb(linear.at(k, 0).g) * 255.0f), k);
        EXPECT_EQ(std::lround(linearToSrgb(linear.at(k, 0).b) * 255.0f), 255);
    }
}

}  // namespace
}  // namespace caustica
