// The own BVH against the brute-force reference, plus build determinism and statistics.
#include <algorithm>
#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "accel/test_scenes.h"
#include "caustica/accel/bvh.h"
#include "caustica/accel/bvh_traversal.h"

namespace caustica {
namespace {

using test::sceneOf;

/// One traversal variant under test.
struct Variant {
    const char* name;
    bool (*intersect)(const BvhView&, const SceneView&, const Ray&, Hit&);
    bool (*occluded)(const BvhView&, const SceneView&, const Ray&);
};

template <BvhTraversal T, int N = kBvhShortStackSize>
Variant variant(const char* name) {
    return Variant{name, &bvhIntersect<T, N>, &bvhOccluded<T, N>};
}

/// Every traversal, including short stacks of 1 and 2 entries, which lose entries (and so
/// backtrack through the parent links) whenever more than 1 or 2 subtrees are pending, and the
/// stackless one, which backtracks wherever a node has two or more children hit.
std::vector<Variant> allVariants() {
    return {variant<BvhTraversal::Stack>("Stack"),
            variant<BvhTraversal::ShortStack>("ShortStack8"),
            variant<BvhTraversal::ShortStack, 4>("ShortStack4"),
            variant<BvhTraversal::ShortStack, 2>("ShortStack2"),
            variant<BvhTraversal::ShortStack, 1>("ShortStack1"),
            variant<BvhTraversal::Stackless>("Stackless")};
}

/// Casts `numRays` random rays and requires every traversal of the BVH to agree with brute force
/// exactly: same hit or miss, same t bit for bit; a different primId only when it is hit at the
/// very same t (a tie). Occlusion must match too.
void expectMatchesBruteForce(const Scene& scene, const BvhBuildOptions& options, uint32_t numRays,
                             uint64_t seed) {
    const Bvh bvh = buildBvh(scene, options);
    const SceneView view = scene.view();
    const BvhView bvhView = bvh.view();
    if (options.parentLinks && !bvh.nodes.empty()) {
        ASSERT_EQ(bvh.parents.size(), bvh.nodes.size());
    }
    for (const Variant& v : allVariants()) {
        SCOPED_TRACE(v.name);
        uint32_t hits = 0;
        for (const Ray& ray : test::makeRandomRays(scene, numRays, seed)) {
            Hit ref, got;
            const bool refHit = test::bruteForceIntersect(view, ray, ref);
            const bool gotHit = v.intersect(bvhView, view, ray, got);
            ASSERT_EQ(gotHit, refHit);
            ASSERT_EQ(v.occluded(bvhView, view, ray), refHit);
            if (!refHit) {
                EXPECT_FALSE(got.valid());
                continue;
            }
            ++hits;
            ASSERT_EQ(got.t, ref.t);
            // All variants test the leaves in the same order, so they agree with the stack
            // traversal even on ties.
            Hit stackHit;
            ASSERT_TRUE(bvhIntersect(bvhView, view, ray, stackHit));
            EXPECT_EQ(got.primId, stackHit.primId);
            if (got.primId != ref.primId) {
                EXPECT_EQ(test::primitiveT(view, got.primId, ray), ref.t) << "not a tie";
            } else {
                EXPECT_EQ(got.b1, ref.b1);
                EXPECT_EQ(got.b2, ref.b2);
            }
        }
        if (scene.numPrimitives() > 0) {
            EXPECT_GT(hits, numRays / 10);  // the rays do test something
        }
    }
}

struct BvhCase {
    std::string name;
    test::RandomSceneOptions scene;
};

class BvhVsBruteForce : public ::testing::TestWithParam<BvhCase> {};

TEST_P(BvhVsBruteForce, PrecomputedPrimitives) {
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), {}, 3000, 17);
}

TEST_P(BvhVsBruteForce, BinaryNodes) {
    BvhBuildOptions options;
    options.width = 2;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 1500, 23);
}

TEST_P(BvhVsBruteForce, SceneArraysAndOtherSettings) {
    BvhBuildOptions options;
    options.precomputePrimitives = false;
    options.binCount = 8;
    options.maxLeafSize = 2;
    options.width = 3;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 2000, 29);
}

TEST_P(BvhVsBruteForce, FourWideNodes) {
    BvhBuildOptions options;
    options.width = 4;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 1500, 41);
}

TEST_P(BvhVsBruteForce, LargeLeavesInGroupsOfFour) {
    // Leaves of up to 16 primitives: the host tests them four at a time (triangle4.h), including
    // a last group of one to three and groups that hold spheres.
    BvhBuildOptions options;
    options.maxLeafSize = 16;
    options.traversalCost = 8;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 1500, 43);
}

TEST_P(BvhVsBruteForce, SahPerPrimitive) {
    // leafGroup 1: the SAH of the 4-wide BVH before group tests (leaves of mixed sizes).
    BvhBuildOptions options;
    options.leafGroup = 1;
    options.traversalCost = 1;
    options.maxLeafSize = 8;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 1500, 47);
}

TEST_P(BvhVsBruteForce, OneLeafPerPrimitiveBinary) {
    // The deepest trees the builder makes: backtracking climbs through many levels.
    BvhBuildOptions options;
    options.width = 2;
    options.maxLeafSize = 1;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 1000, 31);
}

TEST_P(BvhVsBruteForce, WithoutParentLinks) {
    // The backtracking variants then find parents by descending from the root.
    BvhBuildOptions options;
    options.parentLinks = false;
    expectMatchesBruteForce(test::makeRandomScene(GetParam().scene), options, 500, 37);
}

std::vector<BvhCase> bvhCases() {
    std::vector<BvhCase> cases;
    cases.push_back({"Empty", sceneOf(0, 0, 1)});
    cases.push_back({"OneTriangle", sceneOf(1, 0, 2)});
    cases.push_back({"OneSphere", sceneOf(0, 1, 3)});
    cases.push_back({"SmallMixed", sceneOf(7, 3, 4)});
    cases.push_back({"Triangles1000", sceneOf(1000, 0, 5)});
    cases.push_back({"Mixed2000", sceneOf(1500, 500, 6)});
    BvhCase degenerate{"Degenerate", sceneOf(1000, 50, 7)};
    degenerate.scene.degenerateFraction = 0.3f;
    cases.push_back(degenerate);
    BvhCase far{"FarOffset", sceneOf(1000, 100, 8)};
    far.scene.center = Vec3f(1e4f, -1e4f, 1e4f);
    cases.push_back(far);
    BvhCase dense{"DenseOverlapping", sceneOf(2000, 0, 9)};
    dense.scene.extent = 1;  // heavily overlapping triangles: many near-ties
    cases.push_back(dense);
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Scenes, BvhVsBruteForce, ::testing::ValuesIn(bvhCases()),
                         [](const auto& info) { return info.param.name; });

TEST(Bvh, IdenticalPrimitivesAreSplitByCount) {
    // 100 copies of one triangle: all centroids coincide, so SAH binning has nothing to split on.
    Scene scene;
    const uint32_t mesh = test::addMeshShape(scene, 0, 100);
    for (int i = 0; i < 100; ++i) test::addTriangle(scene, mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    const Bvh bvh = buildBvh(scene);
    EXPECT_GT(bvh.stats.leafCount, 1u);
    Hit hit;
    const Ray ray{{0.25f, 0.25f, 1}, {0, 0, -1}, kInfinity};
    ASSERT_TRUE(bvhIntersect(bvh.view(), scene.view(), ray, hit));
    EXPECT_FLOAT_EQ(hit.t, 1);
    EXPECT_LT(hit.primId, 100u);
}

TEST(Bvh, EmptySceneHasNoNodesAndNoHits) {
    const Scene scene;
    const Bvh bvh = buildBvh(scene);
    EXPECT_TRUE(bvh.nodes.empty());
    EXPECT_EQ(bvh.stats.nodeCount, 0u);
    EXPECT_EQ(bvh.stats.leafCount, 0u);
    Hit hit;
    const Ray ray{{0, 0, 0}, {0, 0, 1}, kInfinity};
    EXPECT_FALSE(bvhIntersect(bvh.view(), scene.view(), ray, hit));
    EXPECT_FALSE(bvhOccluded(bvh.view(), scene.view(), ray));
}

bool sameTree(const Bvh& a, const Bvh& b) {
    if (a.nodes.size() != b.nodes.size() || a.primIndices != b.primIndices) return false;
    // Bitwise: empty slots hold NaN boxes, which never compare equal as floats.
    return std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)) == 0;
}

TEST(Bvh, BuildIsDeterministicForAnyThreadCount) {
    // Large enough for the parallel subtree builds (> 4096 primitives per task).
    const Scene scene = test::makeRandomScene(sceneOf(40000, 2000, 21));
    const Bvh first = buildBvh(scene);
    const Bvh second = buildBvh(scene);
    Bvh serial;
    {
        tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
        serial = buildBvh(scene);
    }
    EXPECT_TRUE(sameTree(first, second));
    EXPECT_TRUE(sameTree(first, serial));
}

bool contains(const Bounds3f& outer, const Bounds3f& inner) {
    return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
           inner.hi.x <= outer.hi.x && inner.hi.y <= outer.hi.y && inner.hi.z <= outer.hi.z;
}

/// Walks the tree from node `index` (whose box is `box`), checking structure and counting.
void checkSubtree(const Bvh& bvh, const Scene& scene, uint32_t index, const Bounds3f& box,
                  uint32_t& leaves, uint32_t& prims, uint32_t& nodes) {
    ++nodes;
    const BvhNode& node = bvh.nodes[index];
    int used = 0;
    for (int k = 0; k < BvhNode::kWidth; ++k) {
        if (node.isEmpty(k)) {
            EXPECT_EQ(node.count[k], 0u);
            continue;
        }
        ++used;
        const Bounds3f child = node.bounds(k);
        ASSERT_TRUE(contains(box, child));
        if (node.isLeaf(k)) {
            ++leaves;
            prims += node.count[k];
            for (uint32_t i = node.offset[k]; i < node.offset[k] + node.count[k]; ++i) {
                ASSERT_LT(i, bvh.primIndices.size());
                ASSERT_TRUE(contains(child, scene.primitiveBounds(bvh.primIndices[i])));
            }
        } else {
            ASSERT_GT(node.offset[k], index);  // depth-first: children after their parent
            ASSERT_LT(node.offset[k], bvh.nodes.size());
            checkSubtree(bvh, scene, node.offset[k], child, leaves, prims, nodes);
        }
    }
    EXPECT_GE(used, index == 0 ? 1 : 2);
}

TEST(Bvh, StatisticsAndStructureAreConsistent) {
    const Scene scene = test::makeRandomScene(sceneOf(5000, 300, 31));
    BvhBuildOptions options;
    const Bvh bvh = buildBvh(scene, options);
    const BvhStats& s = bvh.stats;
    const uint32_t n = scene.numPrimitives();
    EXPECT_EQ(s.nodeCount, bvh.nodes.size());
    EXPECT_EQ(s.width, uint32_t(BvhNode::kWidth));
    EXPECT_LE(s.maxStack, uint32_t(kBvhStackSize));
    EXPECT_GT(s.nodeCount, s.leafCount / 4);
    EXPECT_LT(s.nodeCount, s.leafCount);  // most nodes have more than two children
    EXPECT_EQ(reinterpret_cast<uintptr_t>(bvh.nodes.data()) % 128, 0u);
    EXPECT_LE(s.maxDepth, uint32_t(kBvhMaxDepth));
    EXPECT_GT(s.maxDepth, 3u);
    EXPECT_NEAR(s.averageLeafSize, double(n) / s.leafCount, 1e-9);
    EXPECT_LE(s.averageLeafSize, options.maxLeafSize);
    EXPECT_GT(s.sahCost, 1.0);
    EXPECT_LT(s.sahCost, double(n));  // far better than one big leaf
    EXPECT_EQ(s.memoryBytes, bvh.nodes.size() * sizeof(BvhNode) + n * sizeof(uint32_t) +
                                 n * sizeof(BvhPrimitive) + bvh.nodes.size() * sizeof(uint32_t));
    EXPECT_GE(s.buildMilliseconds, 0.0);

    // Every primitive exactly once; children inside parents; leaves bound their primitives.
    std::vector<uint32_t> ids = bvh.primIndices;
    std::sort(ids.begin(), ids.end());
    for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(ids[i], i);
    uint32_t leaves = 0, prims = 0, nodes = 0;
    checkSubtree(bvh, scene, 0, scene.bounds(), leaves, prims, nodes);
    EXPECT_EQ(leaves, s.leafCount);
    EXPECT_EQ(prims, n);
    EXPECT_EQ(nodes, s.nodeCount);  // every node reachable once
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(bvh.prims[i].primId, bvh.primIndices[i]);

    // Parent links: the root has none, every other node names the slot that points to it.
    ASSERT_EQ(bvh.parents.size(), bvh.nodes.size());
    EXPECT_EQ(bvh.parents[0], kBvhNoParent);
    for (uint32_t i = 1; i < bvh.nodes.size(); ++i) {
        const uint32_t parent = bvh.parents[i] >> kBvhSlotBits;
        const uint32_t slot = bvh.parents[i] & ((1u << kBvhSlotBits) - 1);
        ASSERT_LT(parent, i);
        const BvhNode& p = bvh.nodes[parent];
        EXPECT_FALSE(p.isEmpty(int(slot)));
        EXPECT_FALSE(p.isLeaf(int(slot)));
        EXPECT_EQ(p.offset[slot], i);
    }
}

TEST(Bvh, SinglePrimitiveRootIsALeafSlot) {
    const Scene scene = test::makeRandomScene(sceneOf(0, 1, 3));
    const Bvh bvh = buildBvh(scene);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_TRUE(bvh.nodes[0].isLeaf(0));
    for (int k = 1; k < BvhNode::kWidth; ++k) EXPECT_TRUE(bvh.nodes[0].isEmpty(k));
    EXPECT_EQ(bvh.stats.leafCount, 1u);
}

TEST(Bvh, BinaryWidthGivesTwoChildrenPerNode) {
    const Scene scene = test::makeRandomScene(sceneOf(3000, 0, 32));
    BvhBuildOptions options;
    options.width = 2;
    const Bvh bvh = buildBvh(scene, options);
    EXPECT_EQ(bvh.stats.width, 2u);
    EXPECT_EQ(bvh.stats.nodeCount, bvh.stats.leafCount - 1);  // a full binary tree
    for (const BvhNode& node : bvh.nodes) {
        EXPECT_FALSE(node.isEmpty(1));
        for (int k = 2; k < BvhNode::kWidth; ++k) EXPECT_TRUE(node.isEmpty(k));
    }
}

}  // namespace
}  // namespace caustica
