// stereo_cli_test.cpp — `caustica render --stereo`: a stereo pair written as a multi-view EXR, a
// side-by-side PNG and an anaglyph; stereo options refused with one line when they make no sense.
#include <gtest/gtest.h>

#include <filesystem>
#include <algorithm>
#include <fstream>
#include <utility>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"

namespace caustica::test {
namespace {

class StereoCli : public CliFixture {
protected:
    std::string scene() const {
        const std::string p = path("scene.xml");
        std::ofstream(p) << R"(<scene version="3.0.0"><sensor type="perspective">
            <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/></film></sensor>
            <shape type="sphere"><float name="radius" value="0.5"/><bsdf type="diffuse"/></shape>
            <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter></scene>)";
        return p;
    }
};

TEST_F(StereoCli, WritesMultiViewExrSideBySidePngAndAnaglyph) {
    const CliResult r = runCli("render " + scene() + " --spp 2 -q --stereo off-axis --interocular 0.1 -o " +
                               path("pair.exr") + " -o " + path("pair.png") + " --anaglyph " + path("ana.png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readImage(path("pair.png")).width, 16);
    EXPECT_EQ(readImage(path("ana.png")).width, 8);
    EXPECT_EQ(readImage(path("pair.exr")).width, 8);  // the default view (left) of the multi-view file
    const CliResult s = runCli("render " + scene() + " --spp 1 -q --stereo toe-in --stereo-output separate -o " +
                               path("eyes.exr"));
    ASSERT_EQ(s.exitCode, 0) << s.output;
    EXPECT_TRUE(std::filesystem::exists(path("eyes.left.exr")));
    EXPECT_TRUE(std::filesystem::exists(path("eyes.right.exr")));
}

TEST_F(StereoCli, RefusesBadStereoOptionsWithOneLine) {
    const std::string base = "render " + scene() + " --spp 1 -q -o " + path("x.exr") + " ";
    const std::pair<const char*, const char*> cases[] = {
        {"--interocular 0.1", "--interocular needs --stereo"},
        {"--convergence 2", "--convergence needs --stereo"},
        {"--anaglyph a.png", "--anaglyph needs --stereo"},
        {"--stereo-output separate", "--stereo-output needs --stereo"},
        {"--stereo off-axis --interocular -0.065", "--interocular -0.065"},
        {"--stereo parallel --interocular 0", "--interocular 0"},
        {"--stereo toe-in --convergence -1", "--convergence -1"},
        {"--stereo sideways", "--stereo"},
        {"--stereo off-axis --anaglyph a.jpg", "anaglyph"}};
    for (const auto& [args, says] : cases) {
        const CliResult r = runCli(base + args);
        EXPECT_NE(r.exitCode, 0) << args;
        EXPECT_NE(r.output.find(says), std::string::npos) << args << ": " << r.output;
        EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 3) << args << ": " << r.output;
        EXPECT_FALSE(std::filesystem::exists(path("x.exr"))) << args;
    }
}

}  // namespace
}  // namespace caustica::test
