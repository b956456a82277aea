// colormap.h — the viridis colormap (van der Walt & Smith, matplotlib 2.0): perceptually uniform,
// readable in greyscale and by colour-blind viewers. Evaluated by a degree-6 polynomial fit per
// channel (least-squares fit by M. Zucconi / mattz, shadertoy "Perceptually uniform colormaps",
// max error about 0.013 against matplotlib's table).
#pragma once

#include "caustica/film/image.h"
#include "caustica/util/spectrum.h"

namespace caustica {

/// Viridis at t in [0, 1] (clamped; NaN maps to 0), sRGB-encoded like matplotlib's table.
CA_HD_INLINE Spectrum viridisSrgb(Float t) {
    t = (t > 0) ? min(t, Float(1)) : Float(0);
    const Float c[7][3] = {
        {0.2777273272234177f, 0.005407344544966578f, 0.3340998053353061f},
        {0.1050930431085774f, 1.404613529898575f, 1.384590162594685f},
        {-0.3308618287255563f, 0.214847559468213f, 0.09509516302823659f},
        {-4.634230498983486f, -5.799100973351585f, -19.33244095627987f},
        {6.228269936347081f, 14.17993336680509f, 56.69055260068105f},
        {4.776384997670288f, -13.74514537774601f, -65.35303263337234f},
        {-5.435455855934631f, 4.645852612178535f, 26.3124352495832f},
    };
    Spectrum s;
    for (int ch = 0; ch < 3; ++ch) {
        Float v = c[6][ch];
        for (int i = 5; i >= 0; --i) v = v * t + c[i][ch];  // Horner
        s[ch] = clamp(v, Float(0), Float(1));
    }
    return s;
}

/// Viridis at t in [0, 1] in linear RGB: what an image written through writeImage (which
/// sRGB-encodes PNGs) needs so that the PNG shows the colormap's true colours.
CA_HD_INLINE Spectrum viridis(Float t) {
    Spectrum s = viridisSrgb(t);
    return {srgbToLinear(s.r), srgbToLinear(s.g), srgbToLinear(s.b)};
}

}  // namespace caustica
