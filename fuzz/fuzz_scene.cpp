// fuzz_scene.cpp — libFuzzer target for the Mitsuba 3 XML scene loader (loadScene). The input is
// written to scene.xml in a private directory; beside it lie a tiny OBJ (mesh.obj), ASCII and
// binary PLY meshes (mesh.ply, mesh_bin.ply) and an includable fragment (part.xml), so that
// inputs naming them exercise the include and mesh paths.
#include <vector>

#include "caustica/io/scene_loader.h"
#include "fuzz_common.h"

namespace {

std::string binaryPly() {
    std::string s =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    s.append(reinterpret_cast<const char*>(v), sizeof v);
    s.push_back(char(3));
    const int32_t f[3] = {0, 1, 2};
    s.append(reinterpret_cast<const char*>(f), sizeof f);
    return s;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    using caustica::fuzz::writeFile;
    writeFile("mesh.obj",
              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
              "f 1/1/1 2/2/1 3/1/1 4/2/1\n");
    writeFile("mesh.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    writeFile("mesh_bin.ply", binaryPly());
    writeFile("part.xml",
              "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\" id=\"inc\">"
              "<rgb name=\"reflectance\" value=\"0.5\"/></bsdf>\n</scene>\n");
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace caustica;
    std::string path = fuzz::writeFile("scene.xml", {reinterpret_cast<const char*>(data), size});
    fuzz::expectLoadOrError([&] {
        std::vector<std::string> warnings;
        loadScene(path, {}, &warnings);
    });
    return 0;
}
