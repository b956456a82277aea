// serialized_test.cpp — Mitsuba's .serialized meshes: the loader on the files written by
// scripts/make_serialized.py (versions 3 and 4, single and double precision, several meshes,
// colours skipped) and the `serialized` shape plugin's parameters.
#include "caustica/io/mesh/serialized_loader.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

using meshio::loadSerialized;
using meshio::SerializedMesh;

const std::string kData = CAUSTICA_SOURCE_DIR "/tests/io/data/serialized/";

TEST(SerializedLoader, FirstMeshOfVersion4) {
    const SerializedMesh s = loadSerialized(kData + "two_meshes_v4.serialized");
    EXPECT_EQ(s.name, "quad");
    EXPECT_FALSE(s.faceNormals);
    ASSERT_EQ(s.mesh.positions.size(), 4u);
    ASSERT_EQ(s.mesh.triangles.size(), 2u);
    EXPECT_EQ(s.mesh.positions[1], Vec3f(1, -1, 0));
    ASSERT_TRUE(s.mesh.hasNormals());
    EXPECT_EQ(s.mesh.normals[2], Vec3f(0, 0, 1));
    ASSERT_TRUE(s.mesh.hasUVs());
    EXPECT_EQ(s.mesh.uvs[2].x, 1.0f);  // not flipped
    EXPECT_EQ(s.mesh.uvs[2].y, 1.0f);
    EXPECT_EQ(s.mesh.triangles[1].y, 2u);
    EXPECT_EQ(s.mesh.triangles[1].z, 3u);
}

TEST(SerializedLoader, SecondMeshDoublePrecisionWithColoursSkipped) {
    for (const char* file : {"two_meshes_v4.serialized", "two_meshes_v3.serialized"}) {
        SCOPED_TRACE(file);
        const SerializedMesh s = loadSerialized(kData + file, 1);
        EXPECT_EQ(s.name, std::string(file).find("v4") != std::string::npos ? "tetra" : "");
        ASSERT_EQ(s.mesh.positions.size(), 4u);
        ASSERT_EQ(s.mesh.triangles.size(), 4u);
        EXPECT_EQ(s.mesh.positions[3], Vec3f(0, 0, 1));
        EXPECT_FALSE(s.mesh.hasNormals());
        EXPECT_FALSE(s.mesh.hasUVs());
        EXPECT_EQ(s.mesh.triangles[3].x, 1u);  // indices read after the skipped colours
        EXPECT_EQ(s.mesh.triangles[3].z, 3u);
    }
}

TEST(SerializedLoader, FaceNormalsFlagIsReportedNotApplied) {
    const SerializedMesh s = loadSerialized(kData + "face_normals_flag.serialized");
    EXPECT_TRUE(s.faceNormals);
    EXPECT_TRUE(s.mesh.hasNormals());  // Mitsuba 3.9.1 keeps them too
}

TEST(SerializedLoader, ErrorsNameTheFileAndTheReason) {
    const std::string two = kData + "two_meshes_v4.serialized";
    expectError([&] { loadSerialized(two, 2); }, "two_meshes_v4.serialized", 0,
                "shape_index 2 is out of range (the file has 2 meshes)");
    expectError([&] { loadSerialized(two, -1); }, "two_meshes_v4.serialized", 0,
                "shape_index must not be negative");
    expectError([&] { loadSerialized(kData + "missing.serialized"); }, "missing.serialized", 0,
                "cannot open mesh file");
    TempDir dir;
    expectError([&] { loadSerialized(dir.write("e.serialized", "")); }, "e.serialized", 0,
                "too short");
    // Every prefix of a valid file is refused cleanly (never a crash or a partial mesh).
    std::ifstream in(two, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t n = 0; n + 1 < bytes.size(); n += 3) {
        const std::string path = dir.write("p.serialized", bytes.substr(0, n));
        for (int index : {0, 1}) {
            try {
                loadSerialized(path, index);
                // A prefix may still hold the whole first mesh; it must then be complete.
                EXPECT_EQ(index, 0);
                EXPECT_GT(n, 40u);
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("p.serialized"), std::string::npos);
            }
        }
    }
}

TEST(SerializedLoader, FuzzFindingOffsetNearTwoToThe64) {
    // libFuzzer (fuzz/fuzz_serialized.cpp): a version-4 file whose dictionary entry for mesh 2 is
    // 2^64 - 1; `offset + 4` wrapped around and passed the bounds check.
    const std::string bytes("\x1c\x04\x04\x00\x78\x2f\xff\xff\xff\xff\xff\x93\xff\xff\x00\x1c\x04\xb6\x26\x33\x22\xb9\x07\x33\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\x03\x00\x00\x00", 101);
    TempDir dir;
    const std::string path = dir.write("f.serialized", bytes);
    expectError([&] { loadSerialized(path, 2); }, "f.serialized", 0, "beyond the end of the file");
}

std::string serializedShape(const std::string& params) {
    return "<shape type=\"serialized\"><string name=\"filename\" value=\"" + kData +
           "two_meshes_v4.serialized\"/>" + params + "</shape>";
}

TEST(SerializedShape, ParametersAsMitsuba) {
    TempDir dir;
    Scene a = loadXml(dir, sceneXml(serializedShape("")));
    ASSERT_EQ(a.shapes.size(), 1u);
    EXPECT_EQ(a.triangles.size(), 2u);
    EXPECT_TRUE(a.shapes[0].hasNormals);
    EXPECT_TRUE(a.shapes[0].hasUVs);

    Scene b = loadXml(dir, sceneXml(serializedShape(
                               R"(<integer name="shape_index" value="1"/>
                                  <boolean name="flip_normals" value="true"/>
                                  <transform name="to_world"><translate x="2"/></transform>)")));
    EXPECT_EQ(b.triangles.size(), 4u);
    EXPECT_TRUE(b.shapes[0].hasNormals);  // computed: the mesh has none
    EXPECT_TRUE(b.shapes[0].flipNormals);
    EXPECT_EQ(b.positions[3], Vec3f(2, 0, 1));

    Scene c = loadXml(dir, sceneXml(serializedShape(R"(<boolean name="face_normals" value="true"/>)")));
    EXPECT_FALSE(c.shapes[0].hasNormals);
}

TEST(SerializedShape, ErrorsNameTheXmlLineAndTheMeshFile) {
    TempDir dir;
    const std::string path = dir.write(
        "s.xml", sceneXml("<shape type=\"serialized\">\n<string name=\"filename\" value=\"" +
                          kData + "two_meshes_v4.serialized\"/>\n"
                                  "<integer name=\"shape_index\" value=\"7\"/></shape>"));
    expectError([&] { loadScene(path); }, "s.xml", 4,
                "two_meshes_v4.serialized: shape_index 7 is out of range");
    const std::string neg = dir.write(
        "n.xml", sceneXml("<shape type=\"serialized\">\n<string name=\"filename\" value=\"" +
                          kData + "two_meshes_v4.serialized\"/>\n"
                                  "<integer name=\"shape_index\" value=\"-1\"/></shape>"));
    expectError([&] { loadScene(neg); }, "n.xml", 5, "'shape_index' must not be negative");
}

}  // namespace
}  // namespace caustica::test
