// image.cpp — Image construction and whole-image helpers.
#include "caustica/film/image.h"

#include <algorithm>
#include <string>

#include "caustica/util/error.h"

namespace caustica {

Image::Image(int w, int h) {
    if (w < 0 || h < 0 || uint64_t(w) * uint64_t(h) > kMaxImagePixels)
        throw Error("image size " + std::to_string(w) + " x " + std::to_string(h) +
                    " is negative or too large");
    width = w;
    height = h;
    rgb.assign(3 * pixelCount(), 0.0f);
}

void Image::fill(Spectrum s) {
    for (size_t i = 0; i < pixelCount(); ++i) {
        rgb[3 * i + 0] = s.r;
        rgb[3 * i + 1] = s.g;
        rgb[3 * i + 2] = s.b;
    }
}

bool Image::allFinite() const {
    return std::all_of(rgb.begin(), rgb.end(), [](float v) { return std::isfinite(v); });
}

}  // namespace caustica
