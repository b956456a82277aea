// direct_cli_test.cpp — `caustica render --integrator direct` selects Mitsuba's direct integrator
// over the scene's (the stats JSON names it), renders, and an unknown name is refused.
#include <fstream>
#include <sstream>

#include "e2e/cli_helpers.h"
#include "e2e/render_helpers.h"

namespace caustica::test {
namespace {

using DirectCli = CliFixture;

TEST_F(DirectCli, IntegratorOptionSelectsDirect) {
    const std::string scene = sourcePath("scenes/cornell-box/scene.xml");
    const CliResult r = runCli("render " + scene + " --integrator direct --spp 4 --res 16x16 -q " +
                               "--device cpu --checkpoint-every 0 -o " + path("d.exr") +
                               " --stats-json " + path("stats.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(path("d.exr")));
    std::ifstream in(path("stats.json"));
    std::stringstream json;
    json << in.rdbuf();
    EXPECT_NE(json.str().find("\"integrator\": \"direct\""), std::string::npos) << json.str();
}

TEST_F(DirectCli, UnknownIntegratorNameIsRefused) {
    const std::string scene = sourcePath("scenes/cornell-box/scene.xml");
    const CliResult r =
        runCli("render " + scene + " --integrator bdpt --spp 1 --res 8x8 -q -o " + path("x.exr"));
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("bdpt"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace caustica::test
