// robustness_test.cpp — damaged inputs (every truncation, random byte changes) either load or
// are refused with caustica::Error; never a crash, a hang or another exception type.
#include <random>

#include "caustica/io/mesh/obj_loader.h"
#include "caustica/io/mesh/ply_loader.h"
#include "ply_writer.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

/// Runs `load` on `path`; only success or caustica::Error are acceptable outcomes.
template <class Load>
void expectLoadsOrRefuses(const std::string& path, Load load, const std::string& what) {
    try {
        load(path);
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << what << ": " << e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": unexpected " << typeid(e).name() << ": " << e.what();
    }
}

/// Every prefix (in steps of `step` bytes) and `flips` single-byte corruptions of `original`.
template <class Load>
void damage(const TempDir& dir, const std::string& name, const std::string& original, size_t step,
            int flips, Load load) {
    for (size_t n = 0; n < original.size(); n += step)
        expectLoadsOrRefuses(dir.write(name, original.substr(0, n)), load,
                             name + " cut at " + std::to_string(n));
    std::mt19937 rng(1234);
    for (int i = 0; i < flips; ++i) {
        std::string s = original;
        size_t at = rng() % s.size();
        s[at] = char(rng() % 256);
        expectLoadsOrRefuses(dir.write(name, s), load, name + " byte " + std::to_string(at));
    }
}

TEST(Robustness, DamagedSceneXml) {
    TempDir dir;
    std::string xml = readBytes(CAUSTICA_SOURCE_DIR "/scenes/cornell-box/scene.xml");
    ASSERT_FALSE(xml.empty());
    auto load = [](const std::string& p) {
        std::vector<std::string> w;
        loadScene(p, {}, &w);
    };
    damage(dir, "scene.xml", xml, 13, 300, load);
}

TEST(Robustness, DamagedPly) {
    TempDir dir;
    for (auto format : {PlyWriter::Ascii, PlyWriter::Little, PlyWriter::Big})
        damage(dir, "m.ply", squarePly(format), 1, 300,
               [](const std::string& p) { meshio::loadPly(p); });
}

// Cut anywhere inside the header, on a line boundary or not, a PLY file is refused as truncated.
TEST(Robustness, PlyCutInsideItsHeaderSaysTruncated) {
    TempDir dir;
    const std::string ply = squarePly(PlyWriter::Little);
    const size_t headerEnd = ply.find("end_header") + std::string("end_header").size();
    for (size_t n = std::string("ply").size(); n < headerEnd; ++n) {
        SCOPED_TRACE("cut at " + std::to_string(n));
        const std::string path = dir.write("cut.ply", ply.substr(0, n));
        expectError([&] { meshio::loadPly(path); }, "cut.ply", 0,
                    "PLY header truncated: no 'end_header' before the end of the file");
    }
}

TEST(Robustness, DamagedObj) {
    TempDir dir;
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
        "f 1/1/1 2/2/1 3/1/1 4/2/1\nf -1 -2 -3\n";
    damage(dir, "m.obj", obj, 1, 300, [](const std::string& p) { meshio::loadObj(p); });
}

TEST(Robustness, DeepNestingIsRefused) {
    TempDir dir;
    std::string body;
    for (int i = 0; i < 200; ++i) body += "<bsdf type=\"twosided\">";
    for (int i = 0; i < 200; ++i) body += "</bsdf>";
    std::string path = dir.write("deep.xml", sceneXml(body));
    expectError([&] { loadScene(path); }, "deep.xml", 3, "nested more than 64 levels");
}

}  // namespace
}  // namespace caustica::test
