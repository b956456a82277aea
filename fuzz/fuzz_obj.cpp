// fuzz_obj.cpp — libFuzzer target for the Wavefront OBJ loader (meshio::loadObj).
#include "caustica/io/mesh/obj_loader.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace caustica;
    std::string path = fuzz::writeFile("mesh.obj", {reinterpret_cast<const char*>(data), size});
    fuzz::expectLoadOrError([&] { meshio::loadObj(path, true); });
    return 0;
}
