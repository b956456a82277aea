// ply_loader.h — Stanford PLY meshes (ascii, binary_little_endian, binary_big_endian).
#pragma once

#include <string>

#include "caustica/io/mesh/triangle_mesh.h"

namespace caustica::meshio {

/// Loads `path` into an object-space mesh like Mitsuba 3's ply plugin. Reads the `vertex`
/// element's x, y, z, optional nx, ny, nz and texture coordinates (u/v, texture_u/texture_v,
/// s/t or texture_s/texture_t; not flipped), and the `face` element's `vertex_indices` (or
/// `vertex_index`) list of any integer type with any integer count type; polygons are fan
/// triangulated (0, i-1, i). Other properties and elements are parsed and skipped.
/// Throws caustica::Error(path, line, reason): line is the header or ascii data line (0 for
/// binary data, where the element index is named instead).
TriangleMesh loadPly(const std::string& path);

}  // namespace caustica::meshio
