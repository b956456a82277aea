// fuzz_serialized.cpp — libFuzzer target for Mitsuba's .serialized mesh loader
// (meshio::loadSerialized: header, end-of-file dictionary, zlib stream, counts and indices).
// The first input byte picks shape_index 0..3, the rest is the file.
#include "caustica/io/mesh/serialized_loader.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace caustica;
    if (size == 0) return 0;
    const int index = data[0] & 3;
    std::string path =
        fuzz::writeFile("mesh.serialized", {reinterpret_cast<const char*>(data + 1), size - 1});
    fuzz::expectLoadOrError([&] { meshio::loadSerialized(path, index); });
    return 0;
}
