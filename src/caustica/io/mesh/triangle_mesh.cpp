#include "caustica/io/mesh/triangle_mesh.h"

#include <cmath>

#include "caustica/util/error.h"

namespace caustica::meshio {

namespace {

struct Vec3d {
    double x, y, z;
};
Vec3d toDouble(Vec3f v) {
    return {v.x, v.y, v.z};
}
Vec3d sub(Vec3d a, Vec3d b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec3d a, Vec3d b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
double norm(Vec3d a) {
    return std::sqrt(dot(a, a));
}

/// Angle between two vectors, robust for small and large angles.
double angleBetween(Vec3d a, Vec3d b) {
    return std::atan2(norm(cross(a, b)), dot(a, b));
}

bool finite2(Vec2f v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

}  // namespace

void validateMesh(const TriangleMesh& mesh, const std::string& source) {
    if (mesh.triangles.empty()) throw Error(source, 0, "mesh has no triangles");
    if (mesh.positions.size() >= 0xffffffffull)
        throw Error(source, 0, "mesh has too many vertices (limit 2^32 - 1)");
    if (mesh.hasNormals() && mesh.normals.size() != mesh.positions.size())
        throw Error(source, 0, "internal: normal count differs from vertex count");
    if (mesh.hasUVs() && mesh.uvs.size() != mesh.positions.size())
        throw Error(source, 0, "internal: uv count differs from vertex count");
    const size_t n = mesh.positions.size();
    for (size_t i = 0; i < n; ++i) {
        if (!isFinite(mesh.positions[i]))
            throw Error(source, 0,
                        "vertex " + std::to_string(i) + " has a NaN or infinite position");
        if (mesh.hasNormals() && !isFinite(mesh.normals[i]))
            throw Error(source, 0, "vertex " + std::to_string(i) + " has a NaN or infinite normal");
        if (mesh.hasUVs() && !finite2(mesh.uvs[i]))
            throw Error(source, 0, "vertex " + std::to_string(i) + " has a NaN or infinite uv");
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Vec3u& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] >= n)
                throw Error(source, 0,
                            "triangle " + std::to_string(t) + " references vertex " +
                                std::to_string(tri[k]) + " but the mesh has " + std::to_string(n) +
                                " vertices");
    }
}

void transformMesh(TriangleMesh& mesh, const Transform& toWorld) {
    for (Vec3f& p : mesh.positions) p = toWorld.applyPoint(p);
    for (Vec3f& nrm : mesh.normals) {
        Vec3f n = toWorld.applyNormal(nrm);
        Float len = length(n);
        nrm = len > 0 ? n / len : Vec3f(0);
    }
}

void computeVertexNormals(TriangleMesh& mesh) {
    std::vector<Vec3d> sum(mesh.positions.size(), Vec3d{0, 0, 0});
    for (const Vec3u& tri : mesh.triangles) {
        const Vec3d p[3] = {toDouble(mesh.positions[tri.x]), toDouble(mesh.positions[tri.y]),
                            toDouble(mesh.positions[tri.z])};
        Vec3d n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        double len = norm(n);
        if (!(len > 0)) continue;  // degenerate face: contributes nothing
        n = {n.x / len, n.y / len, n.z / len};
        for (int k = 0; k < 3; ++k) {
            double angle = angleBetween(sub(p[(k + 1) % 3], p[k]), sub(p[(k + 2) % 3], p[k]));
            Vec3d& s = sum[tri[k]];
            s = {s.x + n.x * angle, s.y + n.y * angle, s.z + n.z * angle};
        }
    }
    mesh.normals.resize(mesh.positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        double len = norm(sum[i]);
        mesh.normals[i] =
            len > 0 ? Vec3f(Float(sum[i].x / len), Float(sum[i].y / len), Float(sum[i].z / len))
                    : Vec3f(0);
    }
}

double surfaceArea(const TriangleMesh& mesh) {
    double area = 0;
    for (const Vec3u& tri : mesh.triangles) {
        Vec3d p0 = toDouble(mesh.positions[tri.x]);
        area += 0.5 * norm(cross(sub(toDouble(mesh.positions[tri.y]), p0),
                                 sub(toDouble(mesh.positions[tri.z]), p0)));
    }
    return area;
}

}  // namespace caustica::meshio
