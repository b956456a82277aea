// Watertightness of every intersector on closed meshes: rays aimed exactly at shared edges and
// shared vertices must not slip through the crack between two triangles. A leak in a closed
// refractive mesh (cornell-water's water) lets a path escape the medium: a silently wrong image.
//
// Each target point p lies on a shared edge (a + s (b - a), rounded to float) or is a shared
// vertex. Three kinds of rays, checked with intersect, occluded and the packet queries:
//  - entering: from outside, a direction strictly inside every incident face's inner half-space
//    (down to nearly parallel to the surface), so the ray crosses the surface at p. Its closest
//    hit must come at t <= ~1 and, if it lies at p (not an earlier part of the mesh), face the
//    ray (an outward-wound mesh is entered through front faces): a ray that slips through p
//    finds only the far side from inside, a back face, or nothing.
//  - leaving: from a point inside the mesh, aimed at p: it must hit by t ~ 1, a back face.
//  - inside: from a point inside the mesh, random direction, unbounded: it must hit a back face.
// Embree with RTC_SCENE_FLAG_ROBUST (what caustica renders with) and the own BVH (watertight
// triangle test, primitive_intersect.h) run as tests; Embree without the flag, which leaks, runs
// as DISABLED_ tests that report the leaks.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/bvh.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/accel/intersector.h"
#include "caustica/io/mesh/ply_loader.h"

namespace caustica {
namespace {

using test::TestRng;

/// Double-precision vectors for the test's geometry (face normals, directions).
struct Vec3d {
    double x = 0, y = 0, z = 0;
    Vec3d() = default;
    Vec3d(double a, double b, double c) : x(a), y(b), z(c) {}
    explicit Vec3d(Vec3f v) : x(v.x), y(v.y), z(v.z) {}
    explicit operator Vec3f() const { return Vec3f(Float(x), Float(y), Float(z)); }
    Vec3d operator+(Vec3d o) const { return {x + o.x, y + o.y, z + o.z}; }
    Vec3d operator-(Vec3d o) const { return {x - o.x, y - o.y, z - o.z}; }
    Vec3d operator*(double s) const { return {x * s, y * s, z * s}; }
};
double dot(Vec3d a, Vec3d b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3d normalize(Vec3d v) {
    return v * (1 / std::sqrt(dot(v, v)));
}

/// A closed, outward-wound triangle mesh (one mesh shape) and a box lying inside it.
struct ClosedMesh {
    std::string name;
    Scene scene;
    Bounds3f interior;
};

uint32_t addVertex(Scene& scene, Vec3f p) {
    scene.positions.push_back(p);
    return uint32_t(scene.positions.size() - 1);
}

/// Adds triangle (a, b, c), flipped if needed so that its normal has a positive component along
/// `outward`.
void addOriented(Scene& scene, uint32_t a, uint32_t b, uint32_t c, Vec3f outward) {
    const Vec3f p = scene.positions[a];
    if (dot(cross(scene.positions[b] - p, scene.positions[c] - p), outward) < 0) std::swap(b, c);
    scene.triangles.push_back(Vec3u{a, b, c});
    scene.triangleShape.push_back(0);
}

void finishMesh(Scene& scene) {
    test::addMeshShape(scene, 0, uint32_t(scene.triangles.size()));
}

/// An octahedron subdivided `levels` times (8 * 4^levels triangles, vertices of valence 4 and 6),
/// on a sphere of `radius` around `center`.
ClosedMesh makeOctasphere(Vec3f center, Float radius, int levels) {
    std::vector<Vec3f> unit = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::vector<Vec3u> faces;
    for (uint32_t x : {0u, 1u})
        for (uint32_t y : {2u, 3u})
            for (uint32_t z : {4u, 5u}) faces.push_back({x, y, z});  // addOriented orients them
    for (Vec3f& v : unit) v = normalize(v);
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto mid = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, added] = midpoints.try_emplace(key, uint32_t(unit.size()));
            if (added) unit.push_back(normalize(unit[a] + unit[b]));
            return it->second;
        };
        std::vector<Vec3u> finer;
        for (const Vec3u& f : faces) {
            const uint32_t ab = mid(f.x, f.y), bc = mid(f.y, f.z), ca = mid(f.z, f.x);
            finer.insert(finer.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
        }
        faces = std::move(finer);
    }
    ClosedMesh m{"octasphere", {}, {center - Vec3f(radius / 2), center + Vec3f(radius / 2)}};
    for (const Vec3f& v : unit) addVertex(m.scene, center + v * radius);
    for (const Vec3u& f : faces)
        addOriented(m.scene, f.x, f.y, f.z, m.scene.positions[f.x] - center);
    finishMesh(m.scene);
    return m;
}

/// The box lo + [0, size]^3 with each face an n x n grid of quads split along alternating
/// diagonals; vertices shared between faces (a lattice of (n + 1)^3 points, surface ones used).
ClosedMesh makeSplitCube(Vec3f lo, Float size, int n) {
    ClosedMesh m{"split-cube", {}, {lo + Vec3f(size * 0.1f), lo + Vec3f(size * 0.9f)}};
    std::map<std::tuple<int, int, int>, uint32_t> ids;
    auto vertex = [&](int i, int j, int k) {
        auto [it, added] = ids.try_emplace({i, j, k}, 0);
        if (added)
            it->second = addVertex(m.scene, lo + Vec3f(Float(i), Float(j), Float(k)) * (size / n));
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side <= 1; ++side) {
            Vec3f outward(0);
            outward[axis] = side ? 1.0f : -1.0f;
            auto at = [&](int u, int v) {
                int c[3];
                c[axis] = side * n, c[(axis + 1) % 3] = u, c[(axis + 2) % 3] = v;
                return vertex(c[0], c[1], c[2]);
            };
            for (int u = 0; u < n; ++u)
                for (int v = 0; v < n; ++v) {
                    const uint32_t a = at(u, v), b = at(u + 1, v), c = at(u, v + 1),
                                   d = at(u + 1, v + 1);
                    if ((u + v) % 2) {
                        addOriented(m.scene, a, b, d, outward);
                        addOriented(m.scene, a, d, c, outward);
                    } else {
                        addOriented(m.scene, a, b, c, outward);
                        addOriented(m.scene, b, d, c, outward);
                    }
                }
        }
    finishMesh(m.scene);
    return m;
}

/// A closed tank like cornell-water's water: a wavy n x n height-field top over [-1, 1]^2 (in x
/// and z) around y = 0, a flat grid bottom at y = -1, and four side walls joining the two.
ClosedMesh makeWaterTank(int n) {
    ClosedMesh m{"water-tank", {}, {Vec3f(-0.9f, -0.95f, -0.9f), Vec3f(0.9f, -0.2f, 0.9f)}};
    Scene& s = m.scene;
    auto coord = [&](int i) { return -1 + 2 * Float(i) / Float(n); };
    auto height = [&](Float x, Float z) {
        return 0.06f * std::sin(9 * x + 1) * std::cos(7 * z) + 0.03f * std::sin(23 * x * z);
    };
    const uint32_t top = uint32_t(s.positions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            addVertex(s, Vec3f(coord(i), height(coord(i), coord(j)), coord(j)));
    const uint32_t bottom = uint32_t(s.positions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) addVertex(s, Vec3f(coord(i), -1, coord(j)));
    auto grid = [&](uint32_t base, Vec3f outward) {
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                addOriented(s, a, b, d, outward);
                addOriented(s, a, d, c, outward);
            }
    };
    grid(top, Vec3f(0, 1, 0));
    grid(bottom, Vec3f(0, -1, 0));
    // The side walls: one quad per boundary segment of the grids, walked around the border.
    std::vector<std::pair<int, int>> border;
    for (int i = 0; i < n; ++i) border.push_back({i, 0});
    for (int j = 0; j < n; ++j) border.push_back({n, j});
    for (int i = n; i > 0; --i) border.push_back({i, n});
    for (int j = n; j > 0; --j) border.push_back({0, j});
    for (size_t k = 0; k < border.size(); ++k) {
        const auto [i0, j0] = border[k];
        const auto [i1, j1] = border[(k + 1) % border.size()];
        const uint32_t t0 = top + j0 * (n + 1) + i0, t1 = top + j1 * (n + 1) + i1;
        const uint32_t b0 = bottom + j0 * (n + 1) + i0, b1 = bottom + j1 * (n + 1) + i1;
        const Vec3f mid = (s.positions[t0] + s.positions[t1]) * 0.5f;
        const Vec3f outward(mid.x, 0, mid.z);
        addOriented(s, t0, t1, b1, outward);
        addOriented(s, t0, b1, b0, outward);
    }
    finishMesh(s);
    return m;
}

/// cornell-water's water (meshes/water.ply, object space = world space in its scene).
ClosedMesh loadCornellWater() {
    const meshio::TriangleMesh mesh = meshio::loadPly(std::string(CAUSTICA_SOURCE_DIR) +
                                                      "/scenes/cornell-water/meshes/water.ply");
    // The tank spans the box's [-1, 1] in x and z, the floor to y = -0.2 + waves: points well
    // below the waves are water.
    ClosedMesh m{"cornell-water", {}, {Vec3f(-0.9f, -0.95f, -0.9f), Vec3f(0.9f, -0.6f, 0.9f)}};
    m.scene.positions = mesh.positions;
    m.scene.triangles = mesh.triangles;
    m.scene.triangleShape.assign(mesh.triangles.size(), 0);
    finishMesh(m.scene);
    return m;
}

/// Unit outward normals (double precision) of the triangles.
std::vector<Vec3d> faceNormals(const Scene& scene) {
    std::vector<Vec3d> normals;
    for (const Vec3u& t : scene.triangles) {
        const Vec3d p0(scene.positions[t.x]), p1(scene.positions[t.y]), p2(scene.positions[t.z]);
        normals.push_back(normalize(cross(p1 - p0, p2 - p0)));
    }
    return normals;
}

/// Where rays are aimed: a point and the triangles it lies on (two for an edge, the fan of a
/// vertex).
struct Target {
    Vec3f p;
    std::vector<uint32_t> faces;
    bool vertex;  // else a point of an edge
};

/// For each vertex, the first vertex at the same position: meshes may repeat a position (e.g.
/// where smooth top normals meet flat side normals) and are closed only with those welded.
std::vector<uint32_t> weldedIds(const Scene& scene) {
    std::map<std::tuple<Float, Float, Float>, uint32_t> first;
    std::vector<uint32_t> ids;
    for (uint32_t v = 0; v < scene.positions.size(); ++v) {
        const Vec3f p = scene.positions[v];
        ids.push_back(first.try_emplace({p.x, p.y, p.z}, v).first->second);
    }
    return ids;
}

/// Edges (welded vertex ids) with their faces; fails the test if an edge does not have exactly
/// two (the mesh is not closed).
std::vector<std::pair<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>>> sharedEdges(
    const Scene& scene) {
    const std::vector<uint32_t> weld = weldedIds(scene);
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
    for (uint32_t f = 0; f < scene.triangles.size(); ++f) {
        const Vec3u t = scene.triangles[f];
        const uint32_t v[3] = {weld[t.x], weld[t.y], weld[t.z]};
        for (int k = 0; k < 3; ++k) edges[std::minmax(v[k], v[(k + 1) % 3])].push_back(f);
    }
    size_t open = 0;
    for (const auto& e : edges) open += e.second.size() != 2;
    EXPECT_EQ(open, 0u) << "the mesh is not closed";
    return {edges.begin(), edges.end()};
}

std::vector<Target> makeTargets(const Scene& scene, uint32_t numEdgePoints, uint32_t numVertices,
                                TestRng& rng) {
    const auto edges = sharedEdges(scene);
    const std::vector<uint32_t> weld = weldedIds(scene);
    std::vector<std::vector<uint32_t>> fans(scene.positions.size());
    for (uint32_t f = 0; f < scene.triangles.size(); ++f)
        for (int k = 0; k < 3; ++k) fans[weld[scene.triangles[f][k]]].push_back(f);
    std::vector<Target> targets;
    for (uint32_t i = 0; i < numEdgePoints; ++i) {
        const auto& [ends, faces] = edges[rng.index(uint32_t(edges.size()))];
        const Vec3f a = scene.positions[ends.first], b = scene.positions[ends.second];
        const Float s = rng.uniform();
        targets.push_back({a + (b - a) * s, faces, false});
    }
    for (uint32_t i = 0; i < numVertices; ++i) {
        const uint32_t v = rng.index(uint32_t(scene.positions.size()));
        if (!fans[v].empty()) targets.push_back({scene.positions[v], fans[v], true});
    }
    return targets;
}

/// Least sine of the angle between a ray aimed at a target and each face there: p is rounded to
/// float (about 1e-7 off the edge), so a ray more nearly parallel to a face may truly pass beside
/// the mesh; 1e-3 keeps that offset 1e-4 along the ray, well inside the neighbouring face.
constexpr double kMinSine = 1e-3;

/// A unit direction d with d . n < 0 for every face normal n of the target (it crosses the
/// surface there going in), at a sine `grazing` or more to the mean surface: nearly parallel
/// rays included. False if none was found.
bool enteringDirection(const Target& target, const std::vector<Vec3d>& normals, TestRng& rng,
                       Vec3d& d) {
    Vec3d mean;
    for (uint32_t f : target.faces) mean = mean + normals[f];
    mean = normalize(mean);
    // log-uniform sine of the angle to the surface, from 1e-3 (0.06 degrees) to 1
    double sine = std::pow(10.0, -3.0 * rng.uniform());
    for (int attempt = 0; attempt < 64; ++attempt, sine = std::min(1.0, sine * 1.5)) {
        Vec3d tangent = Vec3d(rng.direction());
        tangent = normalize(tangent - mean * dot(tangent, mean));
        d = tangent * std::sqrt(1 - sine * sine) - mean * sine;
        bool in = true;
        for (uint32_t f : target.faces) in &= dot(d, normals[f]) < -kMinSine;
        if (in) return true;
    }
    return false;
}

/// A ray that failed, for the message.
struct Leak {
    std::string what;
    const struct Probe* probe;
};

/// The rays of one mesh and what each must see.
struct Probe {
    Ray ray;
    bool entering;       // else leaving or inside: the closest hit is a back face
    const char* target;  // "edge", "vertex" or "random" (inside rays in random directions)
};

std::vector<Probe> makeProbes(const ClosedMesh& mesh, uint64_t seed) {
    const Scene& scene = mesh.scene;
    TestRng rng(seed);
    const std::vector<Vec3d> normals = faceNormals(scene);
    const std::vector<Target> targets = makeTargets(scene, 3000, 1000, rng);
    const Float scale = max(mesh.interior.diagonal().x, mesh.interior.diagonal().z);
    std::vector<Probe> probes;
    for (const Target& target : targets) {
        const char* kind = target.vertex ? "vertex" : "edge";
        Vec3d d;
        if (enteringDirection(target, normals, rng, d)) {
            // o + 1 * dir = p; the hit at p comes at t = 1 up to rounding of p and o
            const Vec3f dir = Vec3f(d) * (scale * rng.uniform(0.05f, 2.0f));
            probes.push_back({Ray{target.p - dir, dir, 1.05f}, true, kind});
        }
        // Leaving through p: only where the ray crosses every incident face's plane outward
        // (always on a convex mesh; on a crest of a wavy one it may merely graze a face).
        const Vec3f o = rng.inBox(mesh.interior.lo, mesh.interior.hi);
        bool out = true;
        const Vec3d leave = normalize(Vec3d(target.p - o));
        for (uint32_t f : target.faces) out &= dot(leave, normals[f]) > kMinSine;
        if (out) probes.push_back({Ray{o, target.p - o, 1.05f}, false, kind});
    }
    for (int i = 0; i < 1000; ++i)
        probes.push_back({Ray{rng.inBox(mesh.interior.lo, mesh.interior.hi),
                              rng.direction() * rng.uniform(0.1f, 10.0f), kInfinity},
                          false, "random"});
    return probes;
}

/// "N of M rays leak (edge a, vertex b, random c)" and the first few rays.
std::string describe(const std::vector<Leak>& leaks, size_t total) {
    std::map<std::string, int> byTarget;
    for (const Leak& leak : leaks) ++byTarget[leak.probe->target];
    std::string s = std::to_string(leaks.size()) + " of " + std::to_string(total) + " rays leak (";
    for (const auto& [target, count] : byTarget) s += target + " " + std::to_string(count) + " ";
    s += ")";
    char line[256];
    for (size_t i = 0; i < std::min<size_t>(leaks.size(), 5); ++i) {
        const Ray& r = leaks[i].probe->ray;
        std::snprintf(line, sizeof line,
                      "\n  %s %s: o=(%.9g, %.9g, %.9g) d=(%.9g, %.9g, %.9g) tMax=%g",
                      leaks[i].probe->target, leaks[i].what.c_str(), r.o.x, r.o.y, r.o.z, r.d.x,
                      r.d.y, r.d.z, r.tMax);
        s += line;
    }
    return s;
}

/// Whether the closest hit `hit` (found or not) is right for `probe`.
bool closestHitIsRight(const Scene& scene, const Probe& probe, bool found, const Hit& hit) {
    if (!found || hit.primId >= scene.triangles.size()) return false;
    const Vec3u t = scene.triangles[hit.primId];
    const Vec3f p0 = scene.positions[t.x];
    const Float facing =
        dot(probe.ray.d, cross(scene.positions[t.y] - p0, scene.positions[t.z] - p0));
    // Entering: a front face, or anything up to p (from an origin that turned out to lie in a
    // non-convex mesh, the ray leaves it first, perhaps near p); a back face beyond p means the
    // ray went through.
    if (probe.entering) return facing < 0 || hit.t <= 1.001f;
    return facing > 0;
}

/// Runs every probe through `it` (single-ray intersect and occluded, and the packet queries) and
/// returns the rays that leak.
template <class I>
std::vector<Leak> findLeaks(const I& it, const Scene& scene, const std::vector<Probe>& probes) {
    std::vector<Leak> leaks;
    for (const Probe& probe : probes) {
        Hit hit;
        const bool found = it.intersect(probe.ray, hit);
        if (!closestHitIsRight(scene, probe, found, hit))
            leaks.push_back({found ? (probe.entering ? "entering, went through"
                                                     : "from inside, front face first")
                                   : (probe.entering ? "entering, no hit" : "from inside, no hit"),
                             &probe});
        else if (!it.occluded(probe.ray))
            leaks.push_back({"occluded() false", &probe});
    }
    constexpr int kN = rayPacketSize<I>();
    for (size_t first = 0; first < probes.size(); first += kN) {
        const int n = int(std::min<size_t>(kN, probes.size() - first));
        const Ray* rays[kN];
        Hit hits[kN];
        Hit* hitPtrs[kN];
        uint32_t found[kN], occluded[kN];
        for (int k = 0; k < n; ++k) rays[k] = &probes[first + k].ray, hitPtrs[k] = &hits[k];
        intersectPacket(it, n, rays, hitPtrs, found);
        occludedPacket(it, n, rays, occluded);
        for (int k = 0; k < n; ++k)
            if (!closestHitIsRight(scene, probes[first + k], found[k] != 0, hits[k]) ||
                !occluded[k])
                leaks.push_back({"packet query", &probes[first + k]});
    }
    return leaks;
}

std::vector<ClosedMesh> closedMeshes() {
    std::vector<ClosedMesh> meshes;
    meshes.push_back(makeOctasphere(Vec3f(0.3f, -0.2f, 0.1f), 1.0f, 5));
    meshes.push_back(makeSplitCube(Vec3f(10.25f, -3.5f, 4.0f), 2.0f, 8));
    meshes.push_back(makeWaterTank(48));
    meshes.push_back(loadCornellWater());
    return meshes;
}

const std::vector<ClosedMesh>& meshes() {
    static const std::vector<ClosedMesh> all = closedMeshes();
    return all;
}

TEST(Watertight, TestMeshesAreClosedAndOutwardWound) {
    for (const ClosedMesh& mesh : meshes()) {
        SCOPED_TRACE(mesh.name);
        sharedEdges(mesh.scene);  // fails on an open edge
        double volume = 0;        // divergence theorem: positive for outward winding
        for (const Vec3u& t : mesh.scene.triangles)
            volume +=
                dot(Vec3d(mesh.scene.positions[t.x]),
                    cross(Vec3d(mesh.scene.positions[t.y]), Vec3d(mesh.scene.positions[t.z])));
        EXPECT_GT(volume, 0);
    }
}

/// The probes of meshes()[i], made once.
const std::vector<Probe>& probesOf(size_t i) {
    static const std::vector<std::vector<Probe>> all = [] {
        std::vector<std::vector<Probe>> probes;
        for (size_t m = 0; m < meshes().size(); ++m)
            probes.push_back(makeProbes(meshes()[m], 100 + m));
        return probes;
    }();
    return all[i];
}

using LeakFinder = std::function<std::vector<Leak>(const ClosedMesh&, const std::vector<Probe>&)>;

/// Runs `find` on every mesh with the probes whose target kind `keep` accepts; expects at most
/// `maxLeakFraction` of those rays to leak (a ray counts once, however many queries fail it).
void expectFewLeaks(const char* intersectorName, const LeakFinder& find,
                    const std::function<bool(const Probe&)>& keep, double maxLeakFraction) {
    for (size_t i = 0; i < meshes().size(); ++i) {
        std::vector<Probe> probes;
        for (const Probe& probe : probesOf(i))
            if (keep(probe)) probes.push_back(probe);
        std::vector<Leak> leaks;
        std::set<const Probe*> seen;
        for (const Leak& leak : find(meshes()[i], probes))
            if (seen.insert(leak.probe).second) leaks.push_back(leak);
        EXPECT_LE(double(leaks.size()), maxLeakFraction * double(probes.size()))
            << intersectorName << " on " << meshes()[i].name << ": "
            << describe(leaks, probes.size());
    }
}

bool atEdgeOrRandom(const Probe& p) {
    return std::string(p.target) != "vertex";
}
bool atVertex(const Probe& p) {
    return std::string(p.target) == "vertex";
}

LeakFinder embreeFinder(bool robust) {
    return [robust](const ClosedMesh& mesh, const std::vector<Probe>& probes) {
        const EmbreeScene embree(mesh.scene, EmbreeSceneOptions{robust});
        return findLeaks(embree.intersector(), mesh.scene, probes);
    };
}

template <BvhTraversal Traversal>
std::vector<Leak> bvhLeaks(const ClosedMesh& mesh, const std::vector<Probe>& probes) {
    const Bvh bvh = buildBvh(mesh.scene);
    return findLeaks(BvhIntersectorT<Traversal>{bvh.view(), mesh.scene.view()}, mesh.scene, probes);
}

// What caustica renders with (EmbreeSceneOptions{}: RTC_SCENE_FLAG_ROBUST, Embree's Pluecker
// triangle test): no ray through a shared edge is lost.
TEST(Watertight, EmbreeRobustAtSharedEdges) {
    expectFewLeaks("embree (robust)", embreeFinder(true), atEdgeOrRandom, 0);
}

// At a shared vertex even the robust mode loses a few rays aimed exactly at it (0-2.5% here):
// Embree 3's Pluecker test is watertight along an edge but not at a vertex, where every edge
// function is ~0 and rounding can give them all one sign (embree/embree#387). Without the flag
// 14-31% are lost, so this bound still guards the flag.
TEST(Watertight, EmbreeRobustAtSharedVerticesLosesFew) {
    expectFewLeaks("embree (robust)", embreeFinder(true), atVertex, 0.04);
}

// Known failures, kept to measure (--gtest_also_run_disabled_tests): without the flag Embree uses
// its Moeller-Trumbore test, whose edge functions are not computed identically by the two
// triangles of an edge: 5-13% of the rays aimed exactly at shared edges, 14-31% at vertices are
// lost. The own BVH lost 0.1-9% at edges and 0-6% at vertices with that kind of test.
TEST(Watertight, DISABLED_EmbreeNotRobust) {
    expectFewLeaks("embree (not robust)", embreeFinder(false), atEdgeOrRandom, 0);
}
TEST(Watertight, DISABLED_EmbreeNotRobustAtSharedVertices) {
    expectFewLeaks("embree (not robust)", embreeFinder(false), atVertex, 0);
}

// The own BVH (CPU and GPU, every traversal) with the watertight triangle test of Woop, Benthin
// and Wald, "Watertight Ray/Triangle Intersection", JCGT 2013 (primitive_intersect.h): no ray is
// lost, at shared vertices included, where the double-precision redo of zero edge functions
// decides.
TEST(Watertight, BvhStackAtSharedVertices) {
    expectFewLeaks("bvh (stack)", bvhLeaks<BvhTraversal::Stack>, atVertex, 0);
}
TEST(Watertight, BvhStack) {
    expectFewLeaks("bvh (stack)", bvhLeaks<BvhTraversal::Stack>, atEdgeOrRandom, 0);
}
TEST(Watertight, BvhShortStack) {
    expectFewLeaks("bvh (short stack)", bvhLeaks<BvhTraversal::ShortStack>, atEdgeOrRandom, 0);
}
TEST(Watertight, BvhStackless) {
    expectFewLeaks("bvh (stackless)", bvhLeaks<BvhTraversal::Stackless>, atEdgeOrRandom, 0);
}

}  // namespace
}  // namespace caustica
