// fuzz_exr.cpp — libFuzzer target for the readers of caustica's own EXR layouts (the bytes are the
// file): the layered AOV EXR (io/exr_layers.h readExrLayers, and the denoiser's guides read from
// it, io/exr_feature_layers.h readFeatureLayers: what `caustica denoise` reads) and the multi-view
// stereo EXR with its per-view layers (io/exr_multiview.h readMultiViewExr).
#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/exr_multiview.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace caustica;
    const std::string path = fuzz::writeFile("layers.exr", {reinterpret_cast<const char*>(data), size});
    fuzz::expectLoadOrError([&] { readExrLayers(path); });
    fuzz::expectLoadOrError([&] { readFeatureLayers(path); });
    fuzz::expectLoadOrError([&] { readMultiViewExr(path); });
    return 0;
}
