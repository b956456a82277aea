// spectrum_to_rgb.h — <spectrum> values to linear sRGB as Mitsuba 3's RGB variants convert them
// when a scene is loaded (Properties::get_texture and spectrum_list_to_srgb, Mitsuba 3.9.1).
#pragma once

#include <vector>

#include "caustica/util/spectrum.h"

namespace caustica::mitsuba {

/// How a spectrum is used, which changes Mitsuba's conversion.
enum class SpectrumUse {
    Reflectance,  // weighted by D65, clamped to [0, 1] (Mitsuba: bounded, d65)
    Unbounded,    // weighted by D65, only negatives clamped (conductor eta/k)
    Emission,     // not weighted by D65, only negatives clamped (radiance, intensity)
};

/// A wavelength:value list (wavelengths in nm, strictly increasing, at least two) integrated
/// against the CIE 1931 observer as Mitsuba's spectrum_list_to_srgb: 1000 uniform samples over
/// 360..830 nm, zero outside the list's range, linear interpolation inside, times
/// MI_CIE_Y_NORMALIZATION, then XYZ -> linear sRGB. `clamped` (optional) tells whether the
/// result was clamped (Mitsuba prints a warning then).
Spectrum spectrumListToRgb(const std::vector<double>& wavelengths,
                           const std::vector<double>& values, SpectrumUse use,
                           bool* clamped = nullptr);

/// A single-value spectrum: the value itself, except in an emitter where Mitsuba's RGB mode
/// gives value * xyz_to_srgb(1, 1, 1) (an equal-energy spectrum seen with sRGB's D65 white).
Spectrum uniformSpectrumToRgb(double value, SpectrumUse use);

}  // namespace caustica::mitsuba
