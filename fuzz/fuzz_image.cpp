// fuzz_image.cpp — libFuzzer target for the image readers (readImage, readImageMetadata). The
// first byte chooses the format (0: EXR, 1: PFM, 2: PNG, 3: JPEG, 4: Radiance HDR, modulo 5),
// the rest is the file; each file is read decoded and raw (the bitmap texture's two paths).
#include "caustica/io/image_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace caustica;
    if (size < 1) return 0;
    static const char* const kNames[] = {"image.exr", "image.pfm", "image.png", "image.jpg",
                                         "image.hdr"};
    std::string path =
        fuzz::writeFile(kNames[data[0] % 5], {reinterpret_cast<const char*>(data + 1), size - 1});
    fuzz::expectLoadOrError([&] { readImage(path); });
    fuzz::expectLoadOrError([&] {
        ImageReadOptions raw;
        raw.raw = true;
        readImage(path, raw);
    });
    fuzz::expectLoadOrError([&] { readImageMetadata(path); });
    return 0;
}
