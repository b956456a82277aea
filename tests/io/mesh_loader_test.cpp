// mesh_loader_test.cpp — OBJ and PLY loaders on their own: polygons, indices, attributes, the
// three PLY encodings (ascii and both byte orders, written here), and malformed files.
#include <sys/resource.h>

#include <cstring>

#include "caustica/io/mesh/obj_loader.h"
#include "caustica/io/mesh/ply_loader.h"
#include "ply_writer.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

using meshio::loadObj;
using meshio::loadPly;
using meshio::TriangleMesh;

// ---- OBJ ------------------------------------------------------------------------------------

TEST(ObjLoader, PolygonsAreFanTriangulatedAndCornersShared) {
    TempDir dir;
    std::string path = dir.write("m.obj", R"(# a quad and a pentagon sharing an edge
o thing
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v -1 0.5 0
usemtl whatever
f 1 2 3 4
f 1 -2 5 4 -1
l 1 2
)");
    TriangleMesh m = loadObj(path);
    EXPECT_EQ(m.positions.size(), 5u);  // corners with the same v (no vt/vn) are one vertex
    ASSERT_EQ(m.triangles.size(), 2u + 3u);
    EXPECT_EQ(m.triangles[0].x, 0u);
    EXPECT_EQ(m.triangles[1].y, 2u);  // (0, 2, 3): the fan of the quad
    EXPECT_EQ(m.triangles[1].z, 3u);
    EXPECT_FALSE(m.hasNormals());
    EXPECT_FALSE(m.hasUVs());
}

TEST(ObjLoader, NormalsAndTexCoords) {
    TempDir dir;
    std::string path = dir.write("m.obj", R"(v 0 0 0
v 1 0 0
v 0 1 0
vt 0.25 0.125
vt 1 0
vt 0 1
vn 0 0 2
f 1/1/1 2/2/1 3/3/1
f 1/2/1 3/3/1 2/1/1
)");
    TriangleMesh flipped = loadObj(path);
    ASSERT_TRUE(flipped.hasNormals());
    ASSERT_TRUE(flipped.hasUVs());
    EXPECT_EQ(flipped.positions.size(), 5u);        // (1,1,1) and (1,2,1) differ: separate vertices
    EXPECT_EQ(flipped.normals[0], Vec3f(0, 0, 2));  // the loader does not normalise
    EXPECT_EQ(flipped.uvs[0].x, 0.25f);
    EXPECT_EQ(flipped.uvs[0].y, 0.875f);  // flip_tex_coords: v -> 1 - v
    TriangleMesh raw = loadObj(path, false);
    EXPECT_EQ(raw.uvs[0].y, 0.125f);
}

TEST(ObjLoader, Errors) {
    TempDir dir;
    auto bad = [&](const std::string& text, int line, const std::string& reason) {
        std::string path = dir.write("bad.obj", text);
        expectError([&] { loadObj(path); }, "bad.obj", line, reason);
    };
    bad("v 0 0 0\nv 1 0 0\nv 0 abc 0\nf 1 2 3\n", 3, "bad number 'abc'");
    bad("v 0 0 0\nv 1 0 nan\n", 2, "bad number 'nan'");
    bad("v 0 0\n", 1, "'v' line has 2 numbers");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n", 5,
        "vertex index 9 is out of range (the file has 3)");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/4 2 3\n", 4, "texture coordinate index 4 is out of range");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4, "vertex index -4 is out of range");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "vertex index 0 is out of range");
    bad("v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "face has 2 corners");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 4, "bad index 'x'");
    bad("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n", 4, "malformed face corner");
    bad("v 0 0 0\n", 0, "OBJ file has no faces");
    dir.write("folder.obj/x", "");
    expectError([&] { loadObj(dir.path("folder.obj")); }, "folder.obj", 0, "it is a directory");
    expectError([&] { loadObj(dir.path("missing.obj")); }, "missing.obj", 0,
                "cannot open mesh file");
}

// The text pre-check and tinyobjloader read lines differently (here: the pre-check drops the
// "#t ..." comment inside a face line, tinyobj reads "2/1 3/1 4/1" as three more corners), so
// tinyobj returned texture coordinate index 0 of none: loadObj read attrib.texcoords out of range
// (SIGSEGV; found by fuzz_obj, fuzz/corpus/obj/texcoord_index_behind_comment.obj).
TEST(ObjLoader, FuzzFindingIndexThePreCheckDidNotSee) {
    TempDir dir;
    const char* const fuzzed = R"(v 0 0 0 1
v 1 0 0
v 0 1 0
v 1 0 1
vt[ 0.5 0.5
vn 0 0 1
f 1//1 2//1  3//1#t 2/1 3/1 4/1
g` grp
s3//1
t 2/1 3/1 4/1
g grp
 1
l 1& 
3
f 1 2 1 2
p 12 
3 f3 4
)";
    ASSERT_EQ(std::strlen(fuzzed), 154u);
    std::string path = dir.write("fuzzed.obj", fuzzed);
    expectError([&] { loadObj(path); }, "fuzzed.obj", 0,
                "face 1, corner 4: texture coordinate index 1 is out of range (the file has 0)");
    // The same disagreement for the other index kinds: every index is checked against what
    // tinyobj returned (the pre-check sees 3 corners, tinyobj 4).
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n";
    path = dir.write("v.obj", tri + "f 1 2 3#x 4\n");
    expectError([&] { loadObj(path); }, "v.obj", 0,
                "face 1, corner 4: vertex index 4 is out of range (the file has 3)");
    path = dir.write("vn.obj", tri + "g part\nf 1//1 2//1 3//1#x 1//2\n");
    expectError([&] { loadObj(path); }, "vn.obj", 0,
                "face 1 (group 'part'), corner 4: normal index 2 is out of range (the file has 1)");
}

// tinyobjloader reads each tag line "t name ints/reals/strings" into up to 3 x 8192 values and
// copies all the tags into every shape: 3000 such lines (60 KB) took over 2 GB, out of memory under
// fuzz_obj's limit. caustica uses no tags and hides them from tinyobj, so they cost nothing.
TEST(ObjLoader, TagLinesCostNoMemory) {
    auto peakRssKb = [] {
        rusage u{};
        getrusage(RUSAGE_SELF, &u);
        return long(u.ru_maxrss);  // kilobytes on Linux
    };
    TempDir dir;
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    for (int i = 0; i < 1000; ++i)  // tinyobj also ends a line at '\r' and skips leading blanks
        text += i % 2 ? "t a 8192/8192/8192\n" : " \tt\tb 8192/8192/8192\r";
    const std::string path = dir.write("tags.obj", text);
    const long before = peakRssKb();
    EXPECT_EQ(loadObj(path).triangles.size(), 1u);
    EXPECT_LT(peakRssKb() - before, 128 * 1024) << "loading grew the peak RSS by over 128 MB";
}

// ---- PLY ------------------------------------------------------------------------------------

TEST(PlyLoader, RoundTripsInAllEncodings) {
    TempDir dir;
    for (auto format : {PlyWriter::Ascii, PlyWriter::Little, PlyWriter::Big}) {
        SCOPED_TRACE(int(format));
        TriangleMesh m = loadPly(dir.write("sq.ply", squarePly(format)));
        ASSERT_EQ(m.positions.size(), 5u);
        EXPECT_EQ(m.positions[4], Vec3f(2, 2, 1));
        ASSERT_TRUE(m.hasNormals());
        EXPECT_EQ(m.normals[3], Vec3f(0, 0, 1));
        ASSERT_TRUE(m.hasUVs());
        EXPECT_EQ(m.uvs[2].x, 0.5f);
        EXPECT_EQ(m.uvs[2].y, 0.25f);  // PLY texture coordinates are not flipped
        ASSERT_EQ(m.triangles.size(), 3u);
        EXPECT_EQ(m.triangles[1].x, 0u);  // quad fan (0,1,2), (0,2,3)
        EXPECT_EQ(m.triangles[1].y, 2u);
        EXPECT_EQ(m.triangles[1].z, 3u);
        EXPECT_EQ(m.triangles[2].y, 4u);
    }
}

TEST(PlyLoader, MinimalFilesAndIndexNames) {
    TempDir dir;
    TriangleMesh m = loadPly(dir.write(
        "t.ply",
        "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\n"
        "property float32 x\r\nproperty float32 y\r\nproperty float32 z\r\nelement face 1\r\n"
        "property list int int vertex_index\r\nend_header\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n"
        "3 0 1 2\r\n\r\n"));
    EXPECT_EQ(m.triangles.size(), 1u);
    EXPECT_FALSE(m.hasNormals());
    EXPECT_FALSE(m.hasUVs());
}

TEST(PlyLoader, Errors) {
    TempDir dir;
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    auto bad = [&](const std::string& text, int line, const std::string& reason) {
        std::string path = dir.write("bad.ply", text);
        expectError([&] { loadPly(path); }, "bad.ply", line, reason);
    };
    bad(head + "0 0 0\n1 0 0\n0 x 0\n3 0 1 2\n", 12, "element 'vertex' 2: bad number 'x' for 'y'");
    bad(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", 13,
        "face 0 references vertex 7 but the file has 3");
    bad(head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 13, "face 0 has 2 vertices");
    bad(head + "0 0 0\n1 0 0\n", 11, "file ends before element 'vertex' 2");
    bad(head + "0 0 0\n1 0 0\n0 1 0 5\n3 0 1 2\n", 12, "1 values too many");
    bad(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n9\n", 14, "unexpected data after the last element");
    bad(head + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", 13, "bad uchar value '300'");
    bad("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n", 0, "no 'end_header'");
    bad("ply\nformat ebcdic 1.0\n", 2, "unknown PLY format 'ebcdic'");
    bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty float3 x\nend_header\n", 4,
        "expected 'property <type> <name>'");
    bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nproperty float z\n"
        "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0\n",
        3, "element 'vertex' has no property 'x'");
    bad("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n",
        0, "no 'face' element");
    bad("solid cube\n", 1, "not a PLY file");
    bad(head + "0 0 0\n1 0 0\n0 1 0\n", 0, "file ends before element 'face' 0");
    std::string bin = squarePly(PlyWriter::Little);
    bad(bin.substr(0, bin.size() - 10), 0, "file ends inside element 'face' 1");
    std::string empty =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 0\n"
        "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
    bad(empty, 0, "mesh has no triangles");
}

}  // namespace
}  // namespace caustica::test
