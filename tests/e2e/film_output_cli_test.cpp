// film_output_cli_test.cpp — what `caustica render` writes for an ldrfilm (a tone-mapped PNG by
// default, EXR still linear) and for a crop window (an image of the window's size).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"

namespace caustica::test {
namespace {

class FilmOutput : public CliFixture {
protected:
    /// A scene of a constant environment of radiance 0.5 (nothing else) with film `film`.
    std::string writeScene(const std::string& film) const {
        const std::string p = path("scene.xml");
        std::ofstream(p) << "<scene version=\"3.0.0\"><sensor type=\"perspective\">" << film
                         << "</sensor><emitter type=\"constant\"><rgb name=\"radiance\" "
                            "value=\"0.5\"/></emitter></scene>\n";
        return p;
    }
    /// Runs `caustica ARGS` inside the test's directory; returns the exit code.
    int runIn(const std::string& args) const {
        const std::string cmd = "cd '" + dir.string() + "' && " + CAUSTICA_BINARY + " " + args +
                                " > out.txt 2>&1";
        const int status = std::system(cmd.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
};

TEST_F(FilmOutput, LdrFilmWritesATonemappedPngByDefault) {
    writeScene("<film type=\"ldrfilm\"><integer name=\"width\" value=\"8\"/><integer "
               "name=\"height\" value=\"6\"/><float name=\"exposure\" value=\"0.5\"/></film>");
    ASSERT_EQ(runIn("render scene.xml --spp 1 -q"), 0);
    ASSERT_TRUE(std::filesystem::exists(path("scene.png")));
    EXPECT_FALSE(std::filesystem::exists(path("scene.exr")));
    const Image png = readImage(path("scene.png"));
    EXPECT_EQ(png.width, 8);
    // 0.5 · 2^0.5 through the sRGB curve, quantised to 8 bits, read back as linear.
    const float level = std::round(linearToSrgb(0.5f * std::sqrt(2.0f)) * 255) / 255;
    EXPECT_NEAR(png.at(3, 2).g, srgbToLinear(level), 1e-6);
    // An EXR output of the same render stays linear radiance.
    ASSERT_EQ(runIn("render scene.xml --spp 1 -q -o lin.exr"), 0);
    EXPECT_NEAR(readImage(path("lin.exr")).at(3, 2).g, 0.5f, 1e-6);
}

TEST_F(FilmOutput, HdrFilmDefaultIsExrAndPngIsPlainSrgb) {
    writeScene("<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer "
               "name=\"height\" value=\"6\"/></film>");
    ASSERT_EQ(runIn("render scene.xml --spp 1 -q"), 0);
    EXPECT_TRUE(std::filesystem::exists(path("scene.exr")));
    ASSERT_EQ(runIn("render scene.xml --spp 1 -q -o plain.png"), 0);
    const float level = std::round(linearToSrgb(0.5f) * 255) / 255;
    EXPECT_NEAR(readImage(path("plain.png")).at(3, 2).g, srgbToLinear(level), 1e-6);
}

TEST_F(FilmOutput, CropWindowWritesTheWindow) {
    writeScene("<film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer "
               "name=\"height\" value=\"30\"/><integer name=\"crop_offset_x\" value=\"5\"/>"
               "<integer name=\"crop_width\" value=\"12\"/><integer name=\"crop_height\" "
               "value=\"7\"/></film>");
    ASSERT_EQ(runIn("render scene.xml --spp 1 -q"), 0);
    const Image img = readImage(path("scene.exr"));
    EXPECT_EQ(img.width, 12);
    EXPECT_EQ(img.height, 7);
}

}  // namespace
}  // namespace caustica::test
