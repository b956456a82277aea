// triangle_mesh.h — one triangle mesh as the loaders produce it (object space, local indices),
// and the steps every mesh goes through before it joins the scene.
#pragma once

#include <string>
#include <vector>

#include "caustica/util/transform.h"

namespace caustica::meshio {

/// An indexed triangle mesh. `normals` and `uvs` are either empty (absent) or sized like
/// `positions`; `triangles` index into those arrays.
struct TriangleMesh {
    std::vector<Vec3f> positions;
    std::vector<Vec3f> normals;
    std::vector<Vec2f> uvs;
    std::vector<Vec3u> triangles;

    bool hasNormals() const { return !normals.empty(); }
    bool hasUVs() const { return !uvs.empty(); }
};

/// Checks what the loaders cannot: at least one triangle, indices in range, finite data, array
/// sizes consistent. Throws caustica::Error naming `source` (the mesh file or shape) on failure.
void validateMesh(const TriangleMesh& mesh, const std::string& source);

/// Moves the mesh to world space: positions by `toWorld`, normals by its inverse transpose
/// (renormalised; zero normals stay zero). Triangle winding is kept as it is, like Mitsuba 3:
/// a mirroring transform therefore turns winding-derived (face) normals around.
void transformMesh(TriangleMesh& mesh, const Transform& toWorld);

/// Mitsuba 3's Mesh::recompute_vertex_normals: each vertex gets the sum of its faces' unit
/// normals weighted by the face angle at the vertex (Thürmer and Wüthrich, "Computing Vertex
/// Normals from Polygonal Facets", JGT 3(1), 1998), normalised. Vertices whose faces are all
/// degenerate keep a zero normal (the renderer then falls back to the face normal).
void computeVertexNormals(TriangleMesh& mesh);

/// Sum of the triangle areas (double precision), e.g. to check built-in shapes.
double surfaceArea(const TriangleMesh& mesh);

}  // namespace caustica::meshio
