// sppm_order.h: the k-means order of the visible points (seed 003's hitpoint clustering) is a
// permutation of the Morton order, lowers the k-means objective (sum of squared distances to the
// cluster centres) below that of the Morton chunks it starts from, and is the same on 1 and 2
// threads.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <random>
#include <vector>

#include "caustica/integrators/sppm/sppm_order.h"
#include "caustica/integrators/sppm/sppm_passes.h"
#include "caustica/parallel/buffer.h"

namespace caustica::test {
namespace {

struct Ordered {
    std::vector<uint32_t> list, cluster;
};

/// Points on a few planes and clumps (as visible points on walls and objects), in Morton order.
std::vector<SppmVisiblePoint> scenePoints(uint32_t n) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    std::vector<SppmVisiblePoint> points(n);
    for (uint32_t i = 0; i < n; ++i) {
        const float a = u(rng), b = u(rng);
        switch (i % 3) {
            case 0: points[i].si.p = Vec3f(a, 0, b); break;                                  // floor
            case 1: points[i].si.p = Vec3f(0, a, b); break;                                  // wall
            default: points[i].si.p = Vec3f(0.5f + 0.05f * a, 0.3f + 0.05f * b, u(rng)); break;  // a post
        }
    }
    return points;
}

double objective(const std::vector<SppmVisiblePoint>& points, const std::vector<uint32_t>& list,
                 const std::vector<uint32_t>& cluster) {
    double total = 0;
    for (size_t begin = 0; begin < list.size();) {
        size_t end = begin;
        Vec3f mean(0);
        while (end < list.size() && cluster[end] == cluster[begin]) mean += points[list[end++]].si.p;
        mean = mean * (1 / Float(end - begin));
        for (size_t j = begin; j < end; ++j) total += double(lengthSquared(points[list[j]].si.p - mean));
        begin = end;
    }
    return total;
}

Ordered order(const std::vector<SppmVisiblePoint>& points, bool kmeans) {
    const uint32_t n = uint32_t(points.size());
    Buffer<SppmVisiblePoint> dev(Device::cpu(), n);
    dev.copyFromHost(points);
    Buffer<uint32_t> list(Device::cpu(), n), keys(Device::cpu(), n), home(Device::cpu(), n);
    Buffer<Vec3f> centres(Device::cpu(), n / kKmeansClusterSize + 1);
    std::vector<uint32_t> identity(n);
    for (uint32_t i = 0; i < n; ++i) identity[i] = i;
    list.copyFromHost(identity);
    sppm_detail::mortonKeys(CpuExec{}, n, list.data(), dev.data(), Vec3f(0), Vec3f(1), keys.data());
    radixSortPairs(Device::cpu(), keys.span(), list.span(), 30);
    Ordered o;
    if (kmeans) {
        kmeansOrder(CpuExec{}, n, list.data(), dev.data(), home.data(), keys.data(), centres.data());
        o.cluster = keys.toHost();
    } else {
        o.cluster.resize(n);
        for (uint32_t j = 0; j < n; ++j) o.cluster[j] = j / kKmeansClusterSize;  // the Morton chunks
    }
    o.list = list.toHost();
    return o;
}

TEST(SppmOrder, KmeansClustersAreTighterThanTheMortonChunksItStartsFrom) {
    const std::vector<SppmVisiblePoint> points = scenePoints(6000);
    const Ordered morton = order(points, false), kmeans = order(points, true);
    std::vector<uint32_t> sorted = kmeans.list;
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i) << "not a permutation";
    EXPECT_TRUE(std::is_sorted(kmeans.cluster.begin(), kmeans.cluster.end()));
    const double before = objective(points, morton.list, morton.cluster);
    const double after = objective(points, kmeans.list, kmeans.cluster);
    std::printf("k-means objective: Morton chunks %.4g, after %d Lloyd iterations %.4g\n", before,
                kKmeansIterations, after);
    EXPECT_LT(after, 0.9 * before);
}

TEST(SppmOrder, KmeansIsTheSameOnOneAndTwoThreads) {
    const std::vector<SppmVisiblePoint> points = scenePoints(3000);
    const Ordered one = tbb::task_arena(1).execute([&] { return order(points, true); });
    const Ordered two = tbb::task_arena(2).execute([&] { return order(points, true); });
    EXPECT_EQ(one.list, two.list);
    EXPECT_EQ(one.cluster, two.cluster);
}

}  // namespace
}  // namespace caustica::test
