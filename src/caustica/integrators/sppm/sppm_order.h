// sppm_order.h — the order in which the photon mappers process their visible points (coherence:
// neighbouring work items and memory hold neighbouring points, so that they visit the same cells):
//   morton  the list sorted by the 30-bit Morton code of the points in the scene's box;
//   kmeans  seed 003's clustering of hitpoints: clusters of about kKmeansClusterSize points by
//           Lloyd's k-means, then the list sorted by cluster (Morton order within one). Started
//           from the Morton order cut into chunks of that size (one cluster each); each Lloyd
//           iteration assigns every point to the nearest centre among its own chunk's cluster
//           and the kKmeansReach clusters on either side in Morton order (an exact assignment
//           would cost O(points x clusters)), then moves every centre to the mean of its points
//           (an emptied cluster keeps its centre). No atomics: the same order on any thread count.
// Written once for both devices (named kernels; the driver calls them).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"

namespace caustica {

inline constexpr uint32_t kKmeansClusterSize = 64;  // seed 003: a work group of hitpoints
inline constexpr uint32_t kKmeansReach = 3;          // clusters on either side a point may join
inline constexpr int kKmeansIterations = 4;

namespace sppm_detail {

/// First index j in keys[0, n) with keys[j] >= value (keys ascending).
CA_HD_INLINE uint32_t lowerBound(const uint32_t* keys, uint32_t n, uint32_t value) {
    uint32_t lo = 0, hi = n;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (keys[mid] < value)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/// Centre c = the mean of the points list[sortedAt(j)] of cluster c: the entries j in
/// [lowerBound(c), lowerBound(c + 1)) of `clusterOf` (sorted ascending); unchanged when empty.
template <class Exec>
void clusterMeans(Exec exec, uint32_t clusters, uint32_t count, const uint32_t* clusterOf, const uint32_t* list,
                  const SppmVisiblePoint* points, Vec3f* centres) {
    launch(exec, "sppm.kmeans-means", clusters, [=] CA_HD(size_t c) {
        const uint32_t begin = lowerBound(clusterOf, count, uint32_t(c));
        const uint32_t end = lowerBound(clusterOf, count, uint32_t(c) + 1);
        if (begin == end) return;
        Vec3f sum(0);
        for (uint32_t j = begin; j < end; ++j) sum += points[list[j]].si.p;
        centres[c] = sum * (1 / Float(end - begin));
    });
}

/// Assigns list entry j to the nearest centre among its chunk's cluster (chunk = j / size in
/// the Morton order `home`) and the kKmeansReach clusters either side; ties to the lower id.
template <class Exec>
void assignClusters(Exec exec, uint32_t clusters, uint32_t count, const uint32_t* list, const uint32_t* home,
                    const SppmVisiblePoint* points, const Vec3f* centres, uint32_t* clusterOf) {
    launch(exec, "sppm.kmeans-assign", count, [=] CA_HD(size_t j) {
        const Vec3f p = points[list[j]].si.p;
        const uint32_t h = home[list[j]];
        const uint32_t lo = h > kKmeansReach ? h - kKmeansReach : 0;
        const uint32_t hi = min(clusters - 1, h + kKmeansReach);
        uint32_t best = h;
        Float bestD = lengthSquared(p - centres[h]);
        for (uint32_t c = lo; c <= hi; ++c) {
            const Float d = lengthSquared(p - centres[c]);
            if (d < bestD) {
                bestD = d;
                best = c;
            }
        }
        clusterOf[j] = best;
    });
}

/// The chunks of the Morton-ordered list as the first clusters: home[list[j]] = j / size and
/// clusterOf[j] = the same.
template <class Exec>
void chunkClusters(Exec exec, uint32_t count, const uint32_t* list, uint32_t size, uint32_t* home,
                   uint32_t* clusterOf) {
    launch(exec, "sppm.kmeans-chunks", count, [=] CA_HD(size_t j) {
        home[list[j]] = uint32_t(j) / size;
        clusterOf[j] = uint32_t(j) / size;
    });
}

}  // namespace sppm_detail

/// Reorders list[0, count) (sorted by Morton code) into k-means clusters (see the file comment).
/// home: one entry per visible point index; clusterOf: count entries (on return: each list
/// entry's cluster, ascending); centres: at least ceil(count / kKmeansClusterSize) entries.
template <class Exec>
void kmeansOrder(Exec exec, uint32_t count, uint32_t* list, const SppmVisiblePoint* points, uint32_t* home,
                 uint32_t* clusterOf, Vec3f* centres) {
    if (count == 0) return;
    const uint32_t clusters = (count + kKmeansClusterSize - 1) / kKmeansClusterSize;
    const int bits = std::max(1, 32 - std::countl_zero(clusters));
    sppm_detail::chunkClusters(exec, count, list, kKmeansClusterSize, home, clusterOf);
    sppm_detail::clusterMeans(exec, clusters, count, clusterOf, list, points, centres);
    for (int i = 0; i < kKmeansIterations; ++i) {
        sppm_detail::assignClusters(exec, clusters, count, list, home, points, centres, clusterOf);
        radixSortPairs(Exec::device(), Span<uint32_t>(clusterOf, count), Span<uint32_t>(list, count), bits);
        sppm_detail::clusterMeans(exec, clusters, count, clusterOf, list, points, centres);
    }
}

}  // namespace caustica
