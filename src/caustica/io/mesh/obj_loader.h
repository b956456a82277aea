// obj_loader.h — Wavefront OBJ meshes (tinyobjloader for the parsing, strict checks around it).
#pragma once

#include <string>

#include "caustica/io/mesh/triangle_mesh.h"

namespace caustica::meshio {

/// Loads `path` into an object-space mesh like Mitsuba 3's obj plugin: polygons are fan
/// triangulated (0, i-1, i), corners sharing the same (position, uv, normal) triple become one
/// vertex, `flipTexCoords` maps v to 1 - v (Mitsuba's default). Normals and uvs are absent
/// (empty) when the file has none; mixed files (some corners without a normal) drop them.
/// Materials (mtllib/usemtl), lines and points are ignored.
/// Throws caustica::Error(path, line, reason) for unreadable files, malformed numbers, bad or
/// out-of-range indices, faces with fewer than 3 corners and meshes without faces.
TriangleMesh loadObj(const std::string& path, bool flipTexCoords = true);

}  // namespace caustica::meshio
