// py_arrays.h — render/'s images as numpy arrays (float32, rows top first): an RGB image as
// (H, W, 3), an AOV image as one (H, W, C) array per layer.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "caustica/film/aov_layers.h"
#include "caustica/film/image.h"

namespace caustica::py {

pybind11::array_t<float> imageArray(const Image& image);
/// An (H, W, 3) array (any real dtype, any strides) as an Image; throws caustica::Error naming
/// `what` for another shape.
Image arrayImage(const pybind11::handle& array, const std::string& what);
/// {layer name: (H, W, channels of the layer)} in the spec's order.
pybind11::dict aovArrays(const AovImage& aovs);

}  // namespace caustica::py
