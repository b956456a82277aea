#include "py_images.h"

#include "py_arrays.h"
#include "caustica/film/image_compare.h"
#include "caustica/io/image_io.h"

namespace caustica::py {

namespace pyb = pybind11;
using namespace pybind11::literals;

void bindImages(pyb::module_& m) {
    m.def("read_image", [](const std::string& path) { return imageArray(readImage(path)); }, pyb::arg("path"),
          "Reads an image (.exr, .pfm, .hdr, .png, .jpg) as linear float32 RGB (H, W, 3).");
    m.def("write_image", [](const std::string& path, const pyb::handle& image) {
              writeImage(path, arrayImage(image, "write_image"));
          }, pyb::arg("path"), pyb::arg("image"),
          "Writes an (H, W, 3) array as .exr/.pfm (linear float) or .png (8-bit sRGB).");
    m.def("compare", [](const pyb::handle& test, const pyb::handle& reference) {
              const ErrorMetrics e = compareImages(arrayImage(test, "compare: test"),
                                                   arrayImage(reference, "compare: reference"));
              return pyb::dict("mse"_a = e.mse, "rmse"_a = e.rmse, "relmse"_a = e.relMse, "mae"_a = e.mae,
                               "relmse_worst_share"_a = e.relMseWorstShare, "mean_ratio"_a = e.meanRatio);
          }, pyb::arg("test"), pyb::arg("reference"),
          "Error metrics of `test` against `reference` as `caustica compare` computes them "
          "(relmse = mean (a - b)^2 / (b^2 + 0.01)).");
}

}  // namespace caustica::py
