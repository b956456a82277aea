// eye_seam.h — a stereo film holds two eyes side by side (columns [0, eyeWidth) left,
// [eyeWidth, 2 eyeWidth) right; scene/camera.h). Reconstruction filters, MLT's splatting and
// blurs must never mix the eyes: for them the seam is an image border, clipped and normalised as
// the outer borders are.
#pragma once

#include "caustica/util/math.h"
#include "caustica/util/platform.h"

namespace caustica {

/// The columns [lo, hi] that a filter centred on column x may reach, clipped to the image
/// [0, width) and, on a stereo film (eyeWidth > 0), to x's own eye.
CA_HD_INLINE void eyeColumnRange(int x, int radius, int width, int eyeWidth, int& lo, int& hi) {
    int first = 0, last = width - 1;
    if (eyeWidth > 0) {
        first = x >= eyeWidth ? eyeWidth : 0;
        last = min(last, first + eyeWidth - 1);
    }
    lo = max(first, x - radius);
    hi = min(last, x + radius);
}

}  // namespace caustica
