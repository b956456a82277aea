#include "caustica/io/mesh/shape_meshes.h"

#include <cmath>

namespace caustica::meshio {

TriangleMesh makeRectangle() {
    TriangleMesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.normals.assign(4, Vec3f(0, 0, 1));
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.triangles = {{0, 1, 2}, {2, 3, 0}};
    return m;
}

TriangleMesh makeCube() {
    // Vertex order, normals, uvs and faces of Mitsuba 3's cube shape (src/shapes/cube.cpp).
    static const float kPositions[24][3] = {
        {1, -1, -1}, {1, -1, 1},   {-1, -1, 1}, {-1, -1, -1}, {1, 1, -1},   {-1, 1, -1},
        {-1, 1, 1},  {1, 1, 1},    {1, -1, -1}, {1, 1, -1},   {1, 1, 1},    {1, -1, 1},
        {1, -1, 1},  {1, 1, 1},    {-1, 1, 1},  {-1, -1, 1},  {-1, -1, 1},  {-1, 1, 1},
        {-1, 1, -1}, {-1, -1, -1}, {1, 1, -1},  {1, -1, -1},  {-1, -1, -1}, {-1, 1, -1}};
    static const float kFaceNormals[6][3] = {{0, -1, 0}, {0, 1, 0},  {1, 0, 0},
                                             {0, 0, 1},  {-1, 0, 0}, {0, 0, -1}};
    static const float kUVs[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    TriangleMesh m;
    for (int i = 0; i < 24; ++i) {
        m.positions.emplace_back(kPositions[i][0], kPositions[i][1], kPositions[i][2]);
        const float* n = kFaceNormals[i / 4];
        m.normals.emplace_back(n[0], n[1], n[2]);
        m.uvs.emplace_back(kUVs[i % 4][0], kUVs[i % 4][1]);
    }
    for (uint32_t f = 0; f < 6; ++f) {
        uint32_t b = 4 * f;
        m.triangles.push_back({b + 0, b + 1, b + 2});
        m.triangles.push_back({b + 3, b + 0, b + 2});
    }
    return m;
}

TriangleMesh makeDisk(int segments) {
    TriangleMesh m;
    const uint32_t n = uint32_t(segments);
    // Rim vertices 0..n (n duplicates 0 with v = 1), then one centre vertex per segment.
    for (uint32_t i = 0; i <= n; ++i) {
        double phi = 2.0 * M_PI * double(i % n) / double(n);
        m.positions.emplace_back(Float(std::cos(phi)), Float(std::sin(phi)), 0.0f);
        m.uvs.emplace_back(1.0f, Float(double(i) / double(n)));
    }
    for (uint32_t i = 0; i < n; ++i) {
        m.positions.emplace_back(0.0f, 0.0f, 0.0f);
        m.uvs.emplace_back(0.0f, Float((double(i) + 0.5) / double(n)));
        m.triangles.push_back({n + 1 + i, i, i + 1});
    }
    m.normals.assign(m.positions.size(), Vec3f(0, 0, 1));
    return m;
}

}  // namespace caustica::meshio
