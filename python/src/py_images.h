// py_images.h — image files and error metrics for Python: io/'s readers and writers and
// film/image_compare's metrics (relMSE ...) on numpy arrays, so that scripts compare renders
// against references with caustica's own definitions (docs/PYTHON.md).
#pragma once

#include <pybind11/pybind11.h>

namespace caustica::py {

/// read_image, write_image, compare.
void bindImages(pybind11::module_& m);

}  // namespace caustica::py
