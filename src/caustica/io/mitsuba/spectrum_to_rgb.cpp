// spectrum_to_rgb.cpp — see spectrum_to_rgb.h. The CIE and D65 tables are Mitsuba 3's own
// (cie_table.inc, written by scripts/make_cie_table.py), so the colours agree to float rounding.
#include "caustica/io/mitsuba/spectrum_to_rgb.h"

#include <algorithm>

namespace caustica::mitsuba {

namespace {

#include "caustica/io/mitsuba/cie_table.inc"

/// Mitsuba's cie1931_xyz and cie_d65: the 5 nm tables, linearly interpolated.
void cieAt(double w, double xyz[3], double& d65) {
    const double t = (w - kCieMin) / kCieStep;
    const int k = std::clamp(int(t), 0, kCieSamples - 2);
    const double f = t - k;
    for (int c = 0; c < 3; ++c)
        xyz[c] = kCieTable[k][c] * (1 - f) + kCieTable[k + 1][c] * f;
    d65 = kCieTable[k][3] * (1 - f) + kCieTable[k + 1][3] * f;
}

Spectrum xyzToRgb(const double xyz[3]) {
    double rgb[3];
    for (int r = 0; r < 3; ++r)
        rgb[r] = kXyzToSrgb[r][0] * xyz[0] + kXyzToSrgb[r][1] * xyz[1] + kXyzToSrgb[r][2] * xyz[2];
    return Spectrum(Float(rgb[0]), Float(rgb[1]), Float(rgb[2]));
}

}  // namespace

Spectrum spectrumListToRgb(const std::vector<double>& wl, const std::vector<double>& values,
                           SpectrumUse use, bool* clamped) {
    const bool d65 = use != SpectrumUse::Emission;
    double xyz[3] = {0, 0, 0};
    constexpr int kSteps = 1000;
    for (int i = 0; i < kSteps; ++i) {
        const double w = kCieMin + (i / double(kSteps - 1)) * (kCieMax - kCieMin);
        if (w < wl.front() || w > wl.back()) continue;
        // Last k with wl[k] <= w, kept inside [0, n - 2] (Mitsuba's find_interval).
        const size_t k = std::min<size_t>(
            size_t(std::upper_bound(wl.begin(), wl.end(), w) - wl.begin()) - 1, wl.size() - 2);
        const double w0 = wl[k], w1 = wl[k + 1], v0 = values[k], v1 = values[k + 1];
        const double v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
        double c[3], illum;
        cieAt(w, c, illum);
        const double weight = v * (d65 ? illum : 1.0);
        for (int j = 0; j < 3; ++j) xyz[j] += c[j] * weight;
    }
    for (double& v : xyz) v *= (kCieMax - kCieMin) / kSteps * kCieYNormalization;
    Spectrum rgb = xyzToRgb(xyz);
    Spectrum out = rgb;
    for (int c = 0; c < 3; ++c) {
        out[c] = std::max(out[c], Float(0));
        if (use == SpectrumUse::Reflectance) out[c] = std::min(out[c], Float(1));
    }
    if (clamped) *clamped = out.r != rgb.r || out.g != rgb.g || out.b != rgb.b;
    return out;
}

Spectrum uniformSpectrumToRgb(double value, SpectrumUse use) {
    if (use != SpectrumUse::Emission) return Spectrum(Float(value));
    const double one[3] = {value, value, value};
    return xyzToRgb(one);
}

}  // namespace caustica::mitsuba
