// whitted_cli_test.cpp — `caustica render` runs the whitted integrator when the command line
// (--integrator whitted) or the scene (<integrator type="whitted">) asks for it, its options set
// its parameters, and bad values are refused with the option named; a whitted render saved to a
// checkpoint and resumed ends with the image of the render run straight through.
#include <fstream>
#include <memory>
#include <sstream>

#include "caustica/util/error.h"
#include "e2e/cli_helpers.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

using WhittedCli = CliFixture;

std::string readText(const std::string& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST_F(WhittedCli, IntegratorOptionSelectsWhitted) {
    const std::string scene = sourcePath("scenes/cornell-water/scene.xml");
    const CliResult r = runCli("render " + scene +
                               " --integrator whitted --whitted-max-depth 6 --spp 2 --res 24x24 "
                               "-q --device cpu --checkpoint-every 0 -o " +
                               path("w.exr") + " --stats-json " + path("stats.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(path("w.exr")));
    const std::string json = readText(path("stats.json"));
    EXPECT_NE(json.find("\"integrator\": \"whitted\""), std::string::npos) << json;
}

TEST_F(WhittedCli, SceneIntegratorTypeWhittedIsNative) {
    std::string xml = readText(sourcePath("scenes/cornell-box/scene.xml"));
    const std::string pathTag = "<integrator type=\"path\">";
    ASSERT_NE(xml.find(pathTag), std::string::npos);
    xml.replace(xml.find(pathTag), pathTag.size(), "<integrator type=\"whitted\">");
    std::ofstream(path("box.xml")) << xml;
    const CliResult r = runCli("render " + path("box.xml") +
                               " --spp 1 --res 16x16 -q --device cpu "
                               "--checkpoint-every 0 -o " +
                               path("b.exr") + " --stats-json " + path("stats.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("not supported"), std::string::npos) << r.output;
    EXPECT_NE(readText(path("stats.json")).find("\"integrator\": \"whitted\""), std::string::npos);
}

TEST_F(WhittedCli, BadDepthIsRefusedNamingTheOption) {
    const std::string scene = sourcePath("scenes/cornell-box/scene.xml");
    const CliResult r = runCli("render " + scene +
                               " --integrator whitted --whitted-max-depth -5 --spp 1 --res 8x8 "
                               "-q --device cpu -o " +
                               path("x.exr"));
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("--whitted-max-depth"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("x.exr")));
}

TEST_F(WhittedCli, ResumedRenderEndsWithTheUninterruptedImage) {
    caustica::RenderRequest request;
    request.integrator = "whitted";
    request.device = "cpu";
    request.samplesPerPixel = 6;
    request.samplesPerPass = 2;
    request.seed = 7;
    request.resolution = std::make_pair(24, 24);
    auto renderer = [&] {
        return std::make_unique<Renderer>(loadScene(sourcePath("scenes/cornell-water/scene.xml")),
                                          request);
    };
    auto whole = renderer();
    while (!whole->finished()) whole->step();
    auto first = renderer();
    first->step();
    first->save(path("w.ckpt"));
    auto resumed = renderer();
    resumed->load(path("w.ckpt"));
    EXPECT_EQ(resumed->progress().samplesPerPixel, 2);
    while (!resumed->finished()) resumed->step();
    EXPECT_EQ(resumed->progress().samplesPerPixel, 6);
    EXPECT_TRUE(resumed->develop().rgb == whole->develop().rgb) << "the images differ";
    // A checkpoint of another max_depth is another render.
    request.integratorParams = {
        {"max_depth", IntegratorParam::Kind::Text, "3", "--whitted-max-depth"}};
    EXPECT_THROW(renderer()->load(path("w.ckpt")), Error);
}

}  // namespace
}  // namespace caustica::test
