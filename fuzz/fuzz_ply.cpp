// fuzz_ply.cpp — libFuzzer target for the Stanford PLY loader (meshio::loadPly: header parser,
// ascii and binary readers of either byte order).
#include "caustica/io/mesh/ply_loader.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace caustica;
    std::string path = fuzz::writeFile("mesh.ply", {reinterpret_cast<const char*>(data), size});
    fuzz::expectLoadOrError([&] { meshio::loadPly(path); });
    return 0;
}
