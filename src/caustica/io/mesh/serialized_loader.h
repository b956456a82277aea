// serialized_loader.h — Mitsuba's compressed `.serialized` meshes (the `serialized` shape plugin).
#pragma once

#include <string>

#include "caustica/io/mesh/triangle_mesh.h"

namespace caustica::meshio {

/// One mesh of a `.serialized` file, in object space.
struct SerializedMesh {
    TriangleMesh mesh;
    std::string name;          // version 4 files: the mesh's name ("" in version 3)
    bool faceNormals = false;  // the file's FaceNormals flag (0x0010)
};

/// Loads mesh `shapeIndex` of `path` like Mitsuba 3's serialized plugin. The file is a sequence
/// of meshes, each a little-endian header (uint16 0x041C, uint16 version 3 or 4) followed by a
/// zlib stream: uint32 flags (0x1 normals, 0x2 uvs, 0x8 colours, 0x10 face normals, 0x1000
/// single, 0x2000 double precision), a null-terminated name (version 4), uint64 vertex and
/// triangle counts, positions, optional normals, uvs and colours (skipped), uint32 indices
/// (uint64 when there are more than 2^32 - 1 vertices). The file ends with the byte offset of
/// each mesh (uint64 in version 4, uint32 in version 3) and a uint32 mesh count; it is read only
/// for shapeIndex > 0. uvs are not flipped. Throws caustica::Error(path, 0, reason).
SerializedMesh loadSerialized(const std::string& path, int shapeIndex = 0);

}  // namespace caustica::meshio
