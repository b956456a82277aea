// spatial_test_points.h — point sets, queries and result collection for the spatial/ tests
// (host only). Every structure is compared with BruteForce as sorted index lists, duplicates
// kept, so a point reported twice fails as surely as one missed.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/spatial/brute_force.h"
#include "caustica/spatial/hash_grid.h"
#include "caustica/spatial/kd_tree.h"
#include "caustica/spatial/multi_hash.h"
#include "caustica/spatial/uniform_grid.h"

namespace caustica::test {

/// Positions (and radii) in device memory (the CPU's here) and the PointSet over them.
struct DevicePoints {
    Buffer<Vec3f> positions;
    Buffer<Float> radii;
    Float radius = 0;

    DevicePoints(const std::vector<Vec3f>& p, Float r, const std::vector<Float>& perPoint = {})
        : positions(Device::cpu(), p), radii(Device::cpu(), perPoint), radius(r) {}
    PointSet set() const { return PointSet{positions.constSpan(), radii.constSpan(), radius}; }
};

/// `n` points uniform in the box [lo, hi]^3.
inline std::vector<Vec3f> randomPoints(size_t n, uint64_t seed, Float lo = 0, Float hi = 1) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<Float> u(lo, hi);
    std::vector<Vec3f> p(n);
    for (Vec3f& v : p) v = Vec3f(u(rng), u(rng), u(rng));
    return p;
}

/// `n` points within `spread` of `center` (a caustic: all photons in a tiny region).
inline std::vector<Vec3f> clusteredPoints(size_t n, uint64_t seed, Vec3f center, Float spread) {
    std::vector<Vec3f> p = randomPoints(n, seed, -spread, spread);
    for (Vec3f& v : p) v += center;
    return p;
}

/// Points on a lattice of spacing `step` from the origin: every point on cell boundaries of a
/// grid of cell size `step` (and on the ball's surface of queries of radius `step` at a node).
inline std::vector<Vec3f> latticePoints(int perAxis, Float step) {
    std::vector<Vec3f> p;
    for (int z = 0; z < perAxis; ++z)
        for (int y = 0; y < perAxis; ++y)
            for (int x = 0; x < perAxis; ++x) p.emplace_back(x * step, y * step, z * step);
    return p;
}

/// `n` radii uniform in [lo, hi].
inline std::vector<Float> randomRadii(size_t n, uint64_t seed, Float lo, Float hi) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<Float> u(lo, hi);
    std::vector<Float> r(n);
    for (Float& v : r) v = u(rng);
    return r;
}

/// Query positions: random ones around the points' box, the points themselves, and points
/// displaced by exactly `offset` along an axis (on the surface of balls of radius `offset`).
inline std::vector<Vec3f> queryPoints(const std::vector<Vec3f>& points, Float offset,
                                      uint64_t seed) {
    std::vector<Vec3f> q = randomPoints(200, seed, -0.2f, 1.2f);
    for (size_t i = 0; i < points.size() && i < 200; ++i) {
        q.push_back(points[i]);
        q.push_back(points[i] + Vec3f(offset, 0, 0));
        q.push_back(points[i] - Vec3f(0, 0, offset));
    }
    return q;
}

/// The indices a view's forEachPointWithin reports, sorted (duplicates kept).
template <class View>
std::vector<uint32_t> pointsWithin(const View& view, Vec3f center, Float radius) {
    std::vector<uint32_t> found;
    view.forEachPointWithin(center, radius, [&](uint32_t i) { found.push_back(i); });
    std::sort(found.begin(), found.end());
    return found;
}

/// The indices a view's forEachSphereCovering reports, sorted (duplicates kept).
template <class View>
std::vector<uint32_t> spheresCovering(const View& view, Vec3f x) {
    std::vector<uint32_t> found;
    view.forEachSphereCovering(x, [&](uint32_t i) { found.push_back(i); });
    std::sort(found.begin(), found.end());
    return found;
}

/// The indices a view's forEachSphereOnSegment reports, sorted (duplicates kept).
template <class View>
std::vector<uint32_t> spheresOnSegment(const View& view, Vec3f o, Vec3f d, Float tMax) {
    std::vector<uint32_t> found;
    view.forEachSphereOnSegment(o, d, tMax, [&](uint32_t i) { found.push_back(i); });
    std::sort(found.begin(), found.end());
    return found;
}

/// A view's kNearest result: indices in the order returned, and their squared distances.
struct NearestResult {
    std::vector<uint32_t> indices;
    std::vector<Float> distancesSquared;
    bool operator==(const NearestResult&) const = default;
};

/// Runs view.kNearest(center, k, maxRadius) (the output arrays sized for kMaxNeighbors).
template <class View>
NearestResult nearest(const View& view, Vec3f center, uint32_t k, Float maxRadius) {
    uint32_t indices[kMaxNeighbors];
    Float d2[kMaxNeighbors];
    uint32_t count = 12345;
    view.kNearest(center, k, maxRadius, indices, count, d2);
    return {std::vector<uint32_t>(indices, indices + count), std::vector<Float>(d2, d2 + count)};
}

/// Every point as (|p - center|^2, index), computed as inBall does, sorted ascending: the
/// reference of kNearest written independently of NearestHeap. nearestPrefix cuts it.
inline std::vector<Neighbor> allByDistance(const std::vector<Vec3f>& points, Vec3f center) {
    std::vector<Neighbor> all(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        all[i] = Neighbor{lengthSquared(points[i] - center), uint32_t(i)};
    std::sort(all.begin(), all.end(), [](Neighbor a, Neighbor b) {
        return a.distanceSquared != b.distanceSquared ? a.distanceSquared < b.distanceSquared
                                                      : a.index < b.index;
    });
    return all;
}

/// The first min(k, kMaxNeighbors) of `sorted` that lie within maxRadius (inBall's test).
inline NearestResult nearestPrefix(const std::vector<Neighbor>& sorted, uint32_t k,
                                   Float maxRadius) {
    NearestResult r;
    for (const Neighbor& c : sorted) {
        if (r.indices.size() >= std::min(k, kMaxNeighbors) ||
            !(c.distanceSquared <= maxRadius * maxRadius))
            break;
        r.indices.push_back(c.index);
        r.distancesSquared.push_back(c.distanceSquared);
    }
    return r;
}

/// "query 3 radius 1e-07" (radius left out when negative), for failure messages.
inline std::string queryLabel(size_t q, Float radius = -1) {
    std::ostringstream out;
    out << "query " << q;
    if (radius >= 0) out << " radius " << radius;
    return out.str();
}

/// Compares a structure's result lists with BruteForce's, reporting the first five mismatches,
/// and at the end that some query found something (else the comparison proves nothing).
class ResultCheck {
public:
    explicit ResultCheck(const char* structure) : structure_(structure) {}
    bool enough() const { return failures_ >= 5; }
    void compare(const std::vector<uint32_t>& got, const std::vector<uint32_t>& expected, Vec3f at,
                 const std::string& what) {
        nonEmpty_ += !expected.empty();
        if (got == expected) return;
        ++failures_;
        ADD_FAILURE() << structure_ << ": " << what << " at (" << at.x << ", " << at.y << ", "
                      << at.z << "): " << got.size() << " found, " << expected.size()
                      << " expected";
    }
    void expectSomeFound(bool pointsExist) const {
        if (pointsExist) {
            EXPECT_GT(nonEmpty_, 0u) << "no query found anything: the test proves nothing";
        }
    }

private:
    const char* structure_;
    int failures_ = 0;
    size_t nonEmpty_ = 0;
};

/// The multi-level hash table with tiny leaves and cells of about one point: on the tests'
/// few thousand points a deep tree of many grids at many levels (the default options would
/// give most of them one leaf).
struct MultiHashSmallLeaves : MultiHash {
    MultiHashSmallLeaves(MultiHash m) : MultiHash(std::move(m)) {}
    template <class Exec>
    static MultiHashSmallLeaves build(Exec exec, const PointSet& points) {
        return MultiHash::build(exec, points, MultiHashOptions{16, 1});
    }
};

/// The multi-level hash table with small leaves whose cells are the coarser of the density
/// and radius rules (multi_hash_build.h: chooseLeafLevel).
struct MultiHashCoarserCells : MultiHash {
    MultiHashCoarserCells(MultiHash m) : MultiHash(std::move(m)) {}
    template <class Exec>
    static MultiHashCoarserCells build(Exec exec, const PointSet& points) {
        return MultiHash::build(exec, points, MultiHashOptions{64, 4, MultiHashCellRule::Coarser});
    }
};

/// The uniform grid with cells of one largest radius, narrower than by default (SPPM's photon
/// grid: sppm_driver.h, kSppmGridCellRadii).
struct UniformGridNarrowCells : UniformGrid {
    UniformGridNarrowCells(UniformGrid g) : UniformGrid(std::move(g)) {}
    template <class Exec>
    static UniformGridNarrowCells build(Exec exec, const PointSet& points) {
        return UniformGrid::build(exec, points, 1);
    }
};

/// The structures compared with BruteForce, by name (test messages).
template <class S>
struct StructureName;
#define CAUSTICA_STRUCTURE_NAME(S)                     \
    template <>                                         \
    struct StructureName<S> {                           \
        static constexpr const char* value = #S;        \
    };
CAUSTICA_STRUCTURE_NAME(MultiHash)
CAUSTICA_STRUCTURE_NAME(MultiHashCoarserCells)
CAUSTICA_STRUCTURE_NAME(MultiHashSmallLeaves)
CAUSTICA_STRUCTURE_NAME(BruteForce)
CAUSTICA_STRUCTURE_NAME(KdTree)
CAUSTICA_STRUCTURE_NAME(UniformGrid)
CAUSTICA_STRUCTURE_NAME(UniformGridNarrowCells)
CAUSTICA_STRUCTURE_NAME(HashGrid)
#undef CAUSTICA_STRUCTURE_NAME

/// The structures the query tests compare with BruteForce (typed test suites).
using IndexedStructures =
    ::testing::Types<UniformGrid, UniformGridNarrowCells, HashGrid, KdTree, MultiHash, MultiHashSmallLeaves,
                     MultiHashCoarserCells>;

}  // namespace caustica::test
