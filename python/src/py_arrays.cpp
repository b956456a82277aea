#include "py_arrays.h"

#include <cstring>

#include "caustica/util/error.h"

namespace caustica::py {

namespace pyb = pybind11;

pyb::array_t<float> imageArray(const Image& image) {
    pyb::array_t<float> a({pyb::ssize_t(image.height), pyb::ssize_t(image.width), pyb::ssize_t(3)});
    std::memcpy(a.mutable_data(), image.rgb.data(), image.rgb.size() * sizeof(float));
    return a;
}

Image arrayImage(const pyb::handle& array, const std::string& what) {
    // forcecast: float64 (numpy's default) and other real types convert; C order for the copy.
    const auto a = pyb::array_t<float, pyb::array::c_style | pyb::array::forcecast>::ensure(array);
    if (!a || a.ndim() != 3 || a.shape(2) != 3)
        throw Error(what + ": expected an array of shape (height, width, 3)");
    Image image(int(a.shape(1)), int(a.shape(0)));
    std::memcpy(image.rgb.data(), a.data(), image.rgb.size() * sizeof(float));
    return image;
}

pyb::dict aovArrays(const AovImage& aovs) {
    pyb::dict out;
    const size_t stride = aovs.channels.size();
    size_t first = 0;  // the layer's first channel: layers are consecutive (AovSpec::channelNames)
    for (const AovLayer& layer : aovs.spec.layers) {
        const size_t n = size_t(aovChannelCount(layer.type));
        pyb::array_t<float> a({pyb::ssize_t(aovs.height), pyb::ssize_t(aovs.width), pyb::ssize_t(n)});
        float* dst = a.mutable_data();
        const size_t pixels = size_t(aovs.width) * size_t(aovs.height);
        for (size_t p = 0; p < pixels; ++p)
            for (size_t c = 0; c < n; ++c) dst[p * n + c] = aovs.values[p * stride + first + c];
        out[pyb::str(layer.name)] = std::move(a);
        first += n;
    }
    return out;
}

}  // namespace caustica::py
