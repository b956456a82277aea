// The surface code over lanes (scene/interaction.h, scene/ray.h): triangleSurface, the shading
// frame and offsetRayOrigin on Float4 give each lane the bits of their float forms for that
// lane's inputs — meshes with and without vertex normals (one of them zero), flip_normals, uvs
// and a degenerate uv triangle, dp/du usable or not, points near the origin and far from it.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "caustica/scene/interaction.h"
#include "scene/scene_builder.h"

#if CA_FLOAT4_SSE
namespace caustica::test {
namespace {

bool sameBits(const Vec3f& a, const Vec3f& b) { return std::memcmp(&a, &b, sizeof(Vec3f)) == 0; }
bool sameBits(const Vec2f& a, const Vec2f& b) { return std::memcmp(&a, &b, sizeof(Vec2f)) == 0; }
Vec2f extract(const Vec2F4& v, int k) { return {v.x[k], v.y[k]}; }

/// Six meshes of two triangles, one per case: plain; vertex normals (one zero); flipped with
/// normals; uvs; a degenerate uv triangle; flipped with uvs.
Scene makeMeshes() {
    Scene scene;
    const std::vector<Vec3f> quad = {{-1, -0.5f, 2}, {1.5f, -0.4f, 2.2f}, {1.2f, 1, 1.8f}, {-0.8f, 1.1f, 2.1f}};
    const std::vector<Vec3u> tris = {{0, 1, 2}, {0, 2, 3}};
    const std::vector<Vec3f> normals = {{0.1f, 0.2f, -1}, {0, 0, 0}, {-0.3f, 0.1f, -0.9f}, {0.2f, -0.2f, -1}};
    auto mesh = [&](Vec3f shift, bool withNormals, bool flip, const std::vector<Vec2f>& uvs) {
        std::vector<Vec3f> p = quad;
        for (Vec3f& v : p) v = v + shift;
        const size_t first = scene.uvs.size();
        const uint32_t shape = addMesh(scene, p, tris, flip, withNormals ? normals : std::vector<Vec3f>{});
        scene.shapes[shape].hasUVs = !uvs.empty();
        for (size_t k = 0; k < uvs.size(); ++k) scene.uvs[first + k] = uvs[k];
    };
    const std::vector<Vec2f> uvs = {{0, 0}, {1, 0.1f}, {0.9f, 1}, {0.1f, 0.8f}};
    const std::vector<Vec2f> flat = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
    mesh({0, 0, 0}, false, false, {});
    mesh({3, 0, 0}, true, false, {});
    mesh({-3, 0, 0}, true, true, {});
    mesh({0, 3, 0}, false, false, uvs);
    mesh({0, -3, 0}, false, false, flat);
    mesh({3, 3, 0}, true, true, uvs);
    return scene;
}

TEST(InteractionLanes, TriangleSurfaceGivesEachLaneItsScalarBits) {
    const Scene scene = makeMeshes();
    const SceneView view = scene.view();
    std::mt19937 rng(7);
    std::uniform_int_distribution<uint32_t> prim(0, uint32_t(scene.triangles.size()) - 1);
    std::uniform_real_distribution<float> u(0, 1);
    for (int round = 0; round < 5000; ++round) {
        Index4 ids;
        bool normals[4], flip[4], uvs[4];
        float b1[4], b2[4];
        LaneTriangleSurface<float> want[4];
        for (int k = 0; k < 4; ++k) {
            ids.k[k] = prim(rng);
            const Shape& s = scene.shapes[scene.triangleShape[ids.k[k]]];
            normals[k] = s.hasNormals;
            flip[k] = s.flipNormals;
            uvs[k] = s.hasUVs;
            b1[k] = u(rng);
            b2[k] = (1 - b1[k]) * u(rng);
            if (round % 7 == 0) b1[k] = b2[k] = 0;  // a vertex
            want[k] = triangleSurface<float>(view, ids.k[k], normals[k], flip[k], uvs[k], b1[k], b2[k]);
        }
        const LaneTriangleSurface<Float4> got =
            triangleSurface<Float4>(view, ids, lane::maskOf(normals), lane::maskOf(flip), lane::maskOf(uvs),
                                    Float4::fromLanes(b1[0], b1[1], b1[2], b1[3]),
                                    Float4::fromLanes(b2[0], b2[1], b2[2], b2[3]));
        for (int k = 0; k < 4; ++k) {
            EXPECT_TRUE(sameBits(lane::extract(got.p, k), want[k].p)) << "triangle " << ids.k[k];
            EXPECT_TRUE(sameBits(lane::extract(got.ng, k), want[k].ng)) << "triangle " << ids.k[k];
            EXPECT_TRUE(sameBits(lane::extract(got.ns, k), want[k].ns)) << "triangle " << ids.k[k];
            EXPECT_TRUE(sameBits(lane::extract(got.dpdu, k), want[k].dpdu)) << "triangle " << ids.k[k];
            EXPECT_TRUE(sameBits(lane::extract(got.dpdv, k), want[k].dpdv)) << "triangle " << ids.k[k];
            EXPECT_TRUE(sameBits(extract(got.uv, k), want[k].uv)) << "triangle " << ids.k[k];
        }
    }
}

TEST(InteractionLanes, ComputeInteractionIsTheScalarTriangleSurface) {
    // The mesh with normals: ns interpolated (not the face normal), ng turned towards it.
    const Scene scene = makeMeshes();
    const SceneView view = scene.view();
    const uint32_t prim = 2;  // the first triangle of the second mesh
    const Hit hit{1.0f, prim, 0.3f, 0.2f};
    const SurfaceInteraction si = computeInteraction(view, Ray{{3, 0, 0}, {0, 0, 1}, kInfinity}, hit);
    const LaneTriangleSurface<float> s = triangleSurface<float>(view, prim, true, false, false, 0.3f, 0.2f);
    EXPECT_TRUE(sameBits(si.p, s.p) && sameBits(si.ng, s.ng) && sameBits(si.ns, s.ns) && sameBits(si.dpdu, s.dpdu));
    EXPECT_FALSE(sameBits(si.ns, si.ng) || sameBits(si.ns, -si.ng));
    EXPECT_GT(dot(si.ns, si.ng), 0.0f);
}

TEST(InteractionLanes, ShadingFrameAndRayOffsetGiveEachLaneItsScalarBits) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> c(-1, 1);
    const float scales[] = {1e-3f, 0.02f, 1.0f, 300.0f, 1e6f};
    for (int round = 0; round < 20000; ++round) {
        Vec3f n[4], dpdu[4], p[4], s[4], t[4];
        for (int k = 0; k < 4; ++k) {
            n[k] = normalize(Vec3f(c(rng), c(rng), c(rng)));
            dpdu[k] = Vec3f(c(rng), c(rng), c(rng));
            if ((round + k) % 5 == 0) dpdu[k] = n[k] * 2.0f;  // parallel to n: no usable dp/du
            if ((round + k) % 11 == 0) dpdu[k] = Vec3f(0, 0, 0);
            const float scale = scales[(round + k) % 5];
            p[k] = Vec3f(c(rng), c(rng), c(rng)) * scale;
            shadingFrameAxes<float>(n[k], dpdu[k], s[k], t[k]);
        }
        Vec3F4 s4, t4;
        const Vec3F4 n4 = lane::fromLanes(n[0], n[1], n[2], n[3]);
        shadingFrameAxes<Float4>(n4, lane::fromLanes(dpdu[0], dpdu[1], dpdu[2], dpdu[3]), s4, t4);
        const Vec3F4 o4 = offsetRayOrigin(lane::fromLanes(p[0], p[1], p[2], p[3]), n4);
        for (int k = 0; k < 4; ++k) {
            EXPECT_TRUE(sameBits(lane::extract(s4, k), s[k]));
            EXPECT_TRUE(sameBits(lane::extract(t4, k), t[k]));
            EXPECT_TRUE(sameBits(lane::extract(o4, k), offsetRayOrigin(p[k], n[k])));
        }
    }
}

}  // namespace
}  // namespace caustica::test
#endif  // CA_FLOAT4_SSE
