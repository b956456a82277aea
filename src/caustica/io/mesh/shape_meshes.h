// shape_meshes.h — Mitsuba 3's built-in shapes as object-space triangle meshes.
#pragma once

#include "caustica/io/mesh/triangle_mesh.h"

namespace caustica::meshio {

/// Segments of the disk's triangle fan. A regular N-gon inscribed in the unit circle has area
/// (N/2) sin(2π/N); its relative area error 1 - N sin(2π/N) / (2π) ≈ (2π/N)² / 6 is below 1e-4
/// for N >= 257. With 512 it is 2.5e-5, and the rim is at most 1.9e-5 inside the circle.
inline constexpr int kDiskSegments = 512;

/// Mitsuba's `rectangle`: [-1,1]² in the plane z = 0, normal +z, uv = ((x+1)/2, (y+1)/2).
/// Two triangles with per-vertex normals (Mitsuba's rectangle is analytic and transforms its
/// normal by the inverse transpose, which stored vertex normals reproduce).
TriangleMesh makeRectangle();

/// Mitsuba's `cube`: [-1,1]³, 24 vertices (4 per face), 12 triangles, outward per-face vertex
/// normals and per-face uvs exactly as Mitsuba 3's cube.cpp lays them out.
TriangleMesh makeCube();

/// Mitsuba's `disk`: the unit disk in z = 0, normal +z, uv = (r, φ / 2π) like Mitsuba 3.
/// A fan of `segments` triangles around the centre (one centre vertex per segment so that the
/// uv seam at φ = 0 is not interpolated across).
TriangleMesh makeDisk(int segments = kDiskSegments);

}  // namespace caustica::meshio
