// tonemap.h — Mitsuba 0.6's ldrfilm tone mapping (Mitsuba 3 has no LDR film): radiance ->
// display values in [0, 1] for 8-bit output.
//
//   gamma     v · 2^exposure, then the sRGB curve (gamma = -1) or v^(1/gamma), clamped.
//   reinhard  Reinhard et al. 2002, "Photographic tone reproduction", eqs. 1-4, as Mitsuba 0.6's
//             Bitmap::tonemapReinhard: log-average luminance Lavg = exp(mean(log(1e-3 + Y))),
//             L = Y · key / Lavg, Lwhite = max(Y) · key / Lavg scaled by (1 - burn)^2,
//             Ld = L (1 + L / Lwhite²) / (1 + L); each pixel's RGB scaled by Ld / Y (its
//             chromaticity kept), then the gamma curve as above without exposure.
#pragma once

#include "caustica/film/image.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// Display values in [0, 1] of the linear image under `t` (before 8-bit quantisation).
Image toneMap(const Image& linear, const ToneMapDesc& t);

/// The image whose 8-bit sRGB PNG encoding (io/image_io.h) is exactly round(display · 255) per
/// channel: the linear value of each quantised display level. Use it to write a tone-mapped PNG
/// through writeImage.
Image displayToPngLinear(const Image& display);

}  // namespace caustica
