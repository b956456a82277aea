// `caustica render` under mpirun (built only with MPI and mpirun present): two ranks render the
// single-process image byte for byte; a scene that one rank cannot read ends every rank with that
// rank's message; Ctrl-C saves a checkpoint that resumes with as many ranks and is refused with
// another count; sppm renders one process's image byte for byte too (integer photon sums), mlt
// within the order of its splat sums. Ranks are oversubscribed on CI's two cores, one thread each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "e2e/cli_helpers.h"

namespace caustica::test {
namespace {

const std::string kScene = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-box/scene.xml";
// `timeout`: a hang fails the test instead of blocking CI. OpenMPI 4 settings for containers, as
// environment variables (another MPI ignores them): start the ranks without ssh (plm isolated: one
// host), and no single-copy transfers (they need ptrace, which containers often forbid).
const std::string kMpirun = std::string("OMPI_MCA_plm=isolated OMPI_MCA_btl_vader_single_copy_mechanism=none "
                                        "timeout 60 ") +
                            CAUSTICA_MPIEXEC + " --allow-run-as-root --oversubscribe";
const std::string kRender = std::string(CAUSTICA_BINARY) + " render ";
const std::string kSmall = " --res 24x18 --spp-per-pass 2 --threads 1 -q ";

std::string readFile(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// The floats of a PFM file written by caustica ("PF\nW H\n-1\n", then little-endian floats).
std::vector<float> pfmFloats(const std::string& bytes) {
    size_t at = 0;
    for (int lines = 0; lines < 3 && at < bytes.size(); ++at)
        if (bytes[at] == '\n') ++lines;
    std::vector<float> v((bytes.size() - at) / sizeof(float));
    std::memcpy(v.data(), bytes.data() + at, v.size() * sizeof(float));
    return v;
}

using MpiCli = CliFixture;

TEST_F(MpiCli, TwoRanksRenderTheSppmImageOfOneProcessByteForByte) {
    const std::string glass = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/glass-caustic/scene.xml";
    const std::string args = glass + kSmall + "--integrator sppm --sppm-photons 20000 --spp 3 -o ";
    const CliResult alone = runCli("render " + args + path("alone.pfm"));
    ASSERT_EQ(alone.exitCode, 0) << alone.output;
    const CliResult two = runCliCommand(kMpirun + " -n 2 " + kRender + args + path("two.pfm") + " 2>&1");
    ASSERT_EQ(two.exitCode, 0) << two.output;
    const std::string image = readFile(path("two.pfm"));
    EXPECT_FALSE(image.empty());
    EXPECT_TRUE(image == readFile(path("alone.pfm")));
}

TEST_F(MpiCli, TwoRanksRenderTheMltImageOfOneProcessUpToTheOrderOfItsSums) {
    const std::string args = kScene + kSmall + "--integrator mlt --mlt-chains 64 --spp 8 -o ";
    const CliResult alone = runCli("render " + args + path("alone.pfm"));
    ASSERT_EQ(alone.exitCode, 0) << alone.output;
    const CliResult two = runCliCommand(kMpirun + " -n 2 " + kRender + args + path("two.pfm") + " 2>&1");
    ASSERT_EQ(two.exitCode, 0) << two.output;
    const std::vector<float> a = pfmFloats(readFile(path("alone.pfm"))), b = pfmFloats(readFile(path("two.pfm")));
    ASSERT_EQ(a.size(), size_t(24 * 18 * 3));
    ASSERT_EQ(b.size(), a.size());
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(b[i], a[i], 1e-4 * std::abs(a[i]) + 1e-6) << "value " << i;
        sum += a[i];
    }
    EXPECT_GT(sum, 0);
}

TEST_F(MpiCli, TwoRanksRenderThePathImageOfOneProcessByteForByte) {
    // 13 spp in passes of 2: the budget ends inside a step, on rank 0.
    const CliResult alone = runCli("render " + kScene + kSmall + "--spp 13 -o " + path("alone.pfm"));
    ASSERT_EQ(alone.exitCode, 0) << alone.output;
    const CliResult two = runCliCommand(kMpirun + " -n 2 " + kRender + kScene + kSmall + "--spp 13 -o " +
                                        path("two.pfm") + " --stats-json " + path("two.json") + " 2>&1");
    ASSERT_EQ(two.exitCode, 0) << two.output;
    EXPECT_EQ(count(two.output, "wrote "), 2u) << two.output;  // rank 0 alone writes (image, statistics)
    const std::string image = readFile(path("two.pfm"));
    EXPECT_FALSE(image.empty());
    EXPECT_TRUE(image == readFile(path("alone.pfm")));
    const std::string stats = readFile(path("two.json"));
    EXPECT_NE(stats.find("\"ranks\": 2"), std::string::npos) << stats;
    EXPECT_NE(stats.find("\"samples\": " + std::to_string(24 * 18 * 13)), std::string::npos) << stats;
}

TEST_F(MpiCli, ASceneOneRankCannotReadEndsEveryRankWithItsMessage) {
    // Two hosts that see different files, as two working directories: rank 1's copy of the scene
    // is damaged (mpirun's MPMD form gives each rank its own -wdir).
    std::filesystem::create_directories(dir / "host0");
    std::filesystem::create_directories(dir / "host1");
    std::filesystem::copy_file(kScene, dir / "host0" / "scene.xml");
    std::ofstream(dir / "host1" / "scene.xml") << "<scene version=\"3.0.0\"><shape type=";
    const std::string args = kRender + "scene.xml" + kSmall + "--spp 2 -o out.pfm";
    const CliResult r = runCliCommand(kMpirun + " -n 1 -wdir " + (dir / "host0").string() + " " + args + " : -n 1 -wdir " +
                                      (dir / "host1").string() + " " + args + " 2>&1");
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.exitCode, 124) << "mpirun hung:\n" << r.output;
    // Both ranks print rank 1's one line.
    EXPECT_EQ(count(r.output, "caustica: error: rank 1: scene.xml:1: XML syntax error"), 2u) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "host0" / "out.pfm"));
}

TEST_F(MpiCli, CtrlCSavesACheckpointThatResumesWithAsManyRanksOnly) {
    const std::string render = kRender + kScene + kSmall + "-o " + path("cut.pfm");
    // SIGINT to mpirun, which forwards it to the ranks: they finish the step and rank 0 saves.
    // Sent only once every rank renders (before, a rank still starting has no handler and dies of
    // it, and mpirun with it): the first periodic checkpoint is the sign, since its save is
    // collective and comes after every rank installed its handler. No fixed sleep: a loaded
    // machine may take seconds to start the ranks (timeout 60 ends mpirun if none ever comes).
    const std::string ckpt = path("cut.pfm.ckpt");
    const CliResult cut = runShell(kMpirun + " -n 2 " + render + " --spp 1000000 --checkpoint-every 0.2 > " +
                                   path("cut.log") + " 2>&1 & pid=$!; while [ ! -e " + ckpt +
                                   " ] && kill -0 $pid 2>/dev/null; do sleep 0.05; done; kill -INT $pid; wait $pid; cat " +
                                   path("cut.log"));
    std::smatch m;
    ASSERT_TRUE(std::regex_search(cut.output, m, std::regex("interrupted at ([0-9]+) spp"))) << cut.output;
    ASSERT_TRUE(std::filesystem::exists(ckpt)) << cut.output;
    const std::string interruptedAt = m[1];
    const int total = std::stoi(interruptedAt) + 3;

    const CliResult three = runCliCommand(kMpirun + " -n 3 " + render + " --spp " + std::to_string(total) +
                                          " --resume 2>&1");
    EXPECT_NE(three.exitCode, 0) << three.output;
    EXPECT_NE(three.output.find("written by a render over 2 MPI ranks, resumed with 3 MPI ranks: resume it with "
                                "the same number (mpirun -n 2)"),
              std::string::npos)
        << three.output;

    const CliResult two = runCliCommand(kMpirun + " -n 2 " + render + " --spp " + std::to_string(total) +
                                        " --resume 2>&1");
    ASSERT_EQ(two.exitCode, 0) << two.output;
    // It resumed from the checkpoint Ctrl-C wrote, not from an earlier periodic one.
    EXPECT_NE(two.output.find("resuming from " + ckpt + " at " + interruptedAt + " spp"), std::string::npos)
        << two.output;
    const CliResult alone = runCli("render " + kScene + kSmall + "--spp " + std::to_string(total) + " -o " + path("alone.pfm"));
    ASSERT_EQ(alone.exitCode, 0) << alone.output;
    EXPECT_TRUE(readFile(path("cut.pfm")) == readFile(path("alone.pfm")));
}

}  // namespace
}  // namespace caustica::test
