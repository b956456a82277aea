// tonemap.cpp — ldrfilm tone mapping (see tonemap.h).
#include "caustica/film/tonemap.h"

#include <algorithm>
#include <cmath>

namespace caustica {

namespace {

float encode(float v, float gamma) {
    if (!(v > 0.0f)) return 0.0f;  // also NaN
    v = std::min(v, 1.0f);
    return gamma == -1.0f ? linearToSrgb(v) : std::pow(v, 1.0f / gamma);
}

}  // namespace

Image toneMap(const Image& linear, const ToneMapDesc& t) {
    Image out = linear;
    if (t.method == ToneMapMethod::Reinhard && !linear.empty()) {
        double logSum = 0, maxLum = 0;
        for (int y = 0; y < linear.height; ++y)
            for (int x = 0; x < linear.width; ++x) {
                const double lum = std::max(0.0f, linear.at(x, y).luminance());
                maxLum = std::max(maxLum, lum);
                logSum += std::log(1e-3 + lum);
            }
        const double logAvg = std::exp(logSum / double(linear.pixelCount()));
        const double burn = std::clamp(1.0 - double(t.burn), 1e-8, 1.0);
        const double scale = double(t.key) / logAvg, white = maxLum * scale;
        const double invWhite2 = white > 0 ? 1.0 / (white * white * std::pow(burn, 4.0)) : 0.0;
        for (int y = 0; y < linear.height; ++y)
            for (int x = 0; x < linear.width; ++x) {
                const Spectrum c = linear.at(x, y);
                const double lum = c.luminance();
                if (!(lum > 0)) {
                    out.set(x, y, Spectrum(0.0f));
                    continue;
                }
                const double l = lum * scale;
                const double ld = l * (1 + l * invWhite2) / (1 + l);
                out.set(x, y, c * float(ld / lum));
            }
    } else if (t.method == ToneMapMethod::Gamma) {
        const float multiplier = std::exp2(t.exposure);
        for (float& v : out.rgb) v *= multiplier;
    }
    for (float& v : out.rgb) v = encode(v, t.gamma);
    return out;
}

Image displayToPngLinear(const Image& display) {
    Image out = display;
    for (float& v : out.rgb) {
        const long level = std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f);
        v = srgbToLinear(float(level) / 255.0f);
    }
    return out;
}

}  // namespace caustica
