// shape_test.cpp — shapes as they reach the Scene: built-in meshes (areas, counts, normals),
// analytic spheres (uv and dp/du against Mitsuba's), OBJ/PLY meshes through XML with to_world,
// face_normals and computed normals.
#include <cmath>

#include "caustica/accel/primitive_intersect.h"
#include "caustica/io/mesh/shape_meshes.h"
#include "caustica/scene/interaction.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

double sceneArea(const Scene& s, uint32_t shape) {
    double a = 0;
    const Shape& sh = s.shapes[shape];
    for (uint32_t t = sh.primOffset; t < sh.primOffset + sh.primCount; ++t) {
        const Vec3u& tri = s.triangles[t];
        a += 0.5 * length(cross(s.positions[tri.y] - s.positions[tri.x],
                                s.positions[tri.z] - s.positions[tri.x]));
    }
    return a;
}

Scene oneShape(const std::string& shape, std::vector<std::string>* warnings = nullptr) {
    TempDir dir;
    return loadXml(dir, sceneXml(shape), warnings);
}

TEST(BuiltinShapes, RectangleAreaFollowsToWorld) {
    Scene unit = oneShape("<shape type=\"rectangle\"/>");
    EXPECT_NEAR(sceneArea(unit, 0), 4.0, 1e-6);
    EXPECT_TRUE(unit.shapes[0].hasNormals);
    EXPECT_TRUE(unit.shapes[0].hasUVs);
    EXPECT_EQ(unit.normals[0], Vec3f(0, 0, 1));
    EXPECT_EQ(unit.uvs[2].x, 1.0f);
    Scene scaled = oneShape(R"(<shape type="rectangle"><transform name="to_world">
        <scale x="2" y="3"/><rotate x="1" angle="33"/></transform></shape>)");
    EXPECT_NEAR(sceneArea(scaled, 0), 24.0, 1e-4);
}

TEST(BuiltinShapes, CubeHasTwelveOutwardTriangles) {
    Scene s = oneShape(R"(<shape type="cube"><transform name="to_world">
        <scale value="0.5"/><translate x="3"/></transform></shape>)");
    ASSERT_EQ(s.triangles.size(), 12u);
    EXPECT_EQ(s.positions.size(), 24u);
    EXPECT_NEAR(sceneArea(s, 0), 6.0, 1e-5);
    const Vec3f center(3, 0, 0);
    for (const Vec3u& t : s.triangles) {
        Vec3f a = s.positions[t.x], b = s.positions[t.y], c = s.positions[t.z];
        Vec3f face = cross(b - a, c - a);
        Vec3f out = (a + b + c) / 3 - center;
        EXPECT_GT(dot(face, out), 0);            // winding: outward
        EXPECT_GT(dot(s.normals[t.x], out), 0);  // stored normal: outward
    }
}

TEST(BuiltinShapes, DiskAreaIsPiWithinTolerance) {
    meshio::TriangleMesh disk = meshio::makeDisk();
    EXPECT_NEAR(meshio::surfaceArea(disk), M_PI, 1e-4 * M_PI);
    EXPECT_EQ(disk.triangles.size(), size_t(meshio::kDiskSegments));
    Scene s = oneShape(R"(<shape type="disk"><transform name="to_world">
        <scale value="2"/></transform></shape>)");
    EXPECT_NEAR(sceneArea(s, 0), 4 * M_PI, 4e-4 * M_PI);
    EXPECT_EQ(s.normals[0], Vec3f(0, 0, 1));
}

TEST(BuiltinShapes, Spheres) {
    Scene s = oneShape(R"(
        <shape type="sphere"><point name="center" value="1, 2, 3"/>
            <float name="radius" value="0.5"/></shape>
        <shape type="sphere"><transform name="to_world">
            <scale value="2"/><translate z="-1"/></transform></shape>
        <shape type="sphere"><float name="radius" value="-2"/></shape>
        <shape type="sphere"><boolean name="flip_normals" value="true"/></shape>)");
    ASSERT_EQ(s.spheres.size(), 4u);
    EXPECT_EQ(s.shapes[0].type, ShapeType::Sphere);
    EXPECT_EQ(s.spheres[0].center, Vec3f(1, 2, 3));
    EXPECT_EQ(s.spheres[0].radius, 0.5f);
    EXPECT_EQ(s.spheres[1].center, Vec3f(0, 0, -1));
    EXPECT_EQ(s.spheres[1].radius, 2.0f);
    EXPECT_EQ(s.spheres[2].radius, 2.0f);
    EXPECT_TRUE(s.shapes[2].flipNormals);  // negative radius: Mitsuba turns the normals inwards
    EXPECT_TRUE(s.shapes[3].flipNormals);
    EXPECT_FALSE(s.shapes[0].flipNormals);
    EXPECT_EQ(s.spheres[3].shape, 3u);
    EXPECT_EQ(s.shapes[3].primOffset, 3u);
    TempDir dir;
    std::string bad =
        dir.write("s.xml", sceneXml("<shape type=\"sphere\">\n<transform name=\"to_world\"><scale "
                                    "x=\"2\"/></transform></shape>"));
    expectError([&] { loadScene(bad); }, "s.xml", 3, "to_world must scale uniformly");
}

/// One of Mitsuba 3.9.1's surface interactions (scalar_rgb, scene.ray_intersect) on a sphere hit
/// by the ray from center - 10 d along d.
struct MitsubaSphereHit {
    Vec3f d;
    Vec2f uv;
    Vec3f dpdu, dpdv, n;
};

void expectMitsubaSphereHits(const Scene& s, std::initializer_list<MitsubaSphereHit> hits) {
    const SceneView view = s.view();
    const Sphere& sphere = s.spheres[0];
    for (const MitsubaSphereHit& m : hits) {
        SCOPED_TRACE("d = " + std::to_string(m.d.x) + ", " + std::to_string(m.d.y) + ", " +
                     std::to_string(m.d.z));
        const Ray ray{sphere.center - m.d * 10, m.d, kInfinity};
        Hit hit;
        hit.primId = view.numTriangles();
        ASSERT_TRUE(intersectSphere(ray.o, ray.d, kInfinity, sphere.center, sphere.radius, hit.t));
        const SurfaceInteraction si = computeInteraction(view, ray, hit, true);
        // Without uv (a scene without textures reads none): every other field the same bits.
        const SurfaceInteraction noUv = computeInteraction(view, ray, hit, false);
        EXPECT_EQ(noUv.uv.x, 0.0f);
        EXPECT_EQ(noUv.uv.y, 0.0f);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(noUv.p[i], si.p[i]);
            EXPECT_EQ(noUv.ng[i], si.ng[i]);
            EXPECT_EQ(noUv.ns[i], si.ns[i]);
            EXPECT_EQ(noUv.dpdu[i], si.dpdu[i]);
            EXPECT_EQ(noUv.dpdv[i], si.dpdv[i]);
        }
        // By default uv is there exactly where the scene has textures to read it with.
        EXPECT_EQ(computeInteraction(view, ray, hit).uv.x, 0.0f);
        SceneView textured = view;
        const Texture texture{};
        textured.textures = Span<const Texture>(&texture, 1);
        EXPECT_EQ(computeInteraction(textured, ray, hit).uv.x, si.uv.x);
        EXPECT_NEAR(si.uv.x, m.uv.x, 2e-5);
        EXPECT_NEAR(si.uv.y, m.uv.y, 2e-5);
        EXPECT_NEAR(length(si.dpdu - m.dpdu), 0, 2e-4);
        EXPECT_NEAR(length(si.dpdv - m.dpdv), 0, 2e-4);
        EXPECT_NEAR(length(si.ng - m.n), 0, 2e-5);
    }
}

TEST(BuiltinShapes, SphereUvAndDpduAreTakenInObjectSpaceAsMitsuba) {
    // to_world = translate(1, 2, 3) rotate_y(35) rotate_x(70) scale(0.7).
    expectMitsubaSphereHits(oneShape(R"(<shape type="sphere"><float name="radius" value="0.7"/>
        <transform name="to_world"><rotate x="1" angle="70"/><rotate y="1" angle="35"/>
        <translate x="1" y="2" z="3"/></transform></shape>)"),
                            {{{0.282216f, -0.188144f, -0.940721f},
                              {0.390155f, 0.490004f},
                              {-4.11982f, -1.15943f, -1.00406f},
                              {-0.45112f, 2.08051f, -0.55144f},
                              {-0.28222f, 0.18814f, 0.94072f}},
                             {{-0.9759f, 0.09759f, 0.19518f},
                              {0.057195f, 0.426628f},
                              {0.92693f, 1.37095f, 3.94918f},
                              {0.06051f, 2.07227f, -0.73358f},
                              {0.9759f, -0.09759f, -0.19518f}},
                             {{0.04969f, 0.993808f, -0.099381f},
                              {0.69831f, 0.099056f},
                              {0.81387f, -0.14698f, -1.06285f},
                              {-1.74869f, -0.04584f, -1.3327f},
                              {-0.04969f, -0.99381f, 0.09938f}}});
    // A negative radius mirrors: to_object maps the hit to the antipode, the normals turn inwards.
    expectMitsubaSphereHits(oneShape(R"(<shape type="sphere"><float name="radius" value="-2"/>
        <transform name="to_world"><rotate z="1" angle="40"/></transform></shape>)"),
                            {{{0.282216f, -0.188144f, -0.940721f},
                              {0.795305f, 0.88985f},
                              {-2.36429f, -3.54643f, 0},
                              {4.91802f, -3.27868f, 2.13114f},
                              {0.28222f, -0.18814f, -0.94072f}},
                             {{0.04969f, 0.993808f, -0.099381f},
                              {0.130938f, 0.531686f},
                              {12.48856f, -0.62443f, 0},
                              {0.03118f, 0.62365f, 6.25208f},
                              {0.04969f, 0.99381f, -0.09938f}}});
}

TEST(MeshShapes, ObjThroughXmlWithTransformAndComputedNormals) {
    TempDir dir;
    // A tetrahedron-like open mesh without normals: Mitsuba computes angle-weighted normals.
    dir.write("meshes/tent.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\n");
    Scene s = loadXml(dir, sceneXml(R"(<shape type="obj">
        <string name="filename" value="meshes/tent.obj"/>
        <transform name="to_world"><translate x="10"/></transform>
    </shape>
    <shape type="obj"><string name="filename" value="meshes/tent.obj"/>
        <boolean name="face_normals" value="true"/></shape>)"));
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.positions[1], Vec3f(11, 0, 0));
    EXPECT_TRUE(s.shapes[0].hasNormals);
    // Vertex 0 sits on faces with normals +z (angle 90°) and +y (angle 90°).
    const Float h = std::sqrt(0.5f);
    EXPECT_NEAR(s.normals[0].y, h, 1e-6f);
    EXPECT_NEAR(s.normals[0].z, h, 1e-6f);
    EXPECT_FALSE(s.shapes[1].hasNormals);
    EXPECT_EQ(s.normals[4], Vec3f(0));  // zero-filled
    EXPECT_EQ(s.normals.size(), s.positions.size());
    EXPECT_EQ(s.uvs.size(), s.positions.size());
    EXPECT_FALSE(s.shapes[1].hasUVs);
    EXPECT_EQ(s.triangleShape[2], 1u);
    EXPECT_EQ(s.triangles[2].x, 4u);  // global indices
}

TEST(MeshShapes, PlyNormalsTransformByInverseTranspose) {
    TempDir dir;
    dir.write("n.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
              "0 0 0 1 1 0\n1 0 0 1 1 0\n0 1 0 1 1 0\n3 0 1 2\n");
    Scene s = loadXml(dir, sceneXml(R"(<shape type="ply"><string name="filename" value="n.ply"/>
        <transform name="to_world"><scale x="2"/></transform></shape>)"));
    // (1,1,0) under diag(2,1,1)^-T = (0.5,1,0), normalised.
    const Float len = std::sqrt(1.25f);
    EXPECT_NEAR(s.normals[0].x, 0.5f / len, 1e-6f);
    EXPECT_NEAR(s.normals[0].y, 1.0f / len, 1e-6f);
    EXPECT_EQ(s.positions[1], Vec3f(2, 0, 0));
}

TEST(MeshShapes, MeshFileErrorsNameBothFiles) {
    TempDir dir;
    dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    std::string path = dir.write(
        "scene.xml",
        sceneXml(
            "<shape type=\"obj\">\n<string name=\"filename\" value=\"broken.obj\"/>\n</shape>"));
    expectError([&] { loadScene(path); }, "scene.xml:4:", 4, "broken.obj:4: vertex index 4");
    std::string missing = dir.write(
        "m.xml",
        sceneXml(
            "<shape type=\"ply\">\n<string name=\"filename\" value=\"nowhere.ply\"/>\n</shape>"));
    expectError([&] { loadScene(missing); }, "m.xml", 4, "nowhere.ply: cannot open mesh file");
    std::string nofile = dir.write("f.xml", sceneXml("<shape type=\"obj\"/>"));
    expectError([&] { loadScene(nofile); }, "f.xml", 3, "missing required parameter 'filename'");
}

TEST(MeshShapes, FlipNormalsAndUnknownShapes) {
    Scene s =
        oneShape("<shape type=\"cube\"><boolean name=\"flip_normals\" value=\"true\"/></shape>");
    EXPECT_TRUE(s.shapes[0].flipNormals);
    TempDir dir;
    std::string path = dir.write("u.xml", sceneXml("<shape type=\"torus\"/>"));
    expectError([&] { loadScene(path); }, "u.xml", 3,
                "unsupported shape type 'torus' (supported: cube, cylinder, disk, obj, ply, "
                "rectangle, serialized, sphere)");
}

}  // namespace
}  // namespace caustica::test
