// golden_images_test.cpp — images do not change when the code around the kernels does: each
// bundled scene rendered small at a fixed seed and sample count gives, bit for bit, the image the
// renderer gave before the render session and the single-source drivers (tests/e2e/data/golden,
// made by commit 82801bb's caustica with the commands below; re-made once when the own BVH's
// triangle test became watertight (Woop et al. 2013): its barycentrics and t round differently,
// and the six images moved by relMSE 1.7e-14 to 4.2e-9, means equal; and re-made when rectangle
// lights became sampled as parallelograms (Light::isQuad): the same density on the light, another
// mapping of the random numbers to its points, so these 4-spp images moved by their noise
// (path: relMSE 8e-4 to 8e-3 at 4 spp; at 64x64 and 1024 spp the new and the old path image of
// cornell-water differ by relMSE 6e-5, means equal to 1e-4); and re-made when the warps' sines
// and cosines became polynomials instead of libm's sincosf (sinCosQuarterPi, sinCosTwoPi in
// util/math.h, within 2 ulp): the same paths, directions that differ in their last bits, so the
// six images moved by relMSE 1.4e-15 to 3.7e-12, means equal; and re-made when the own BVH began
// to test rectangles as planes (Bvh::quads, 2026-12-01): their hits' t and barycentrics round
// differently, so cornell-box's and cornell-water's four images moved by relMSE 7.9e-15 to
// 2.6e-9 (door-gap, with more rectangles than the BVH tests as planes, did not). The path tracer's two execution
// modes give that same image; MLT's is compared with sort splats (atomic splats add in an order
// that varies from run to run).
//
// The own BVH is used: Embree picks its kernels by the CPU's instruction set, and its last bits
// differ between machines (tests/accel/embree_test.cpp). A failure here on a new kind of CPU with
// the same code is a libm difference (glibc picks FMA or non-FMA variants at run time), not a
// refactoring: say so and compare against a render of the previous commit on that machine.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"
#include "render_helpers.h"

namespace caustica::test {
namespace {

class GoldenImages : public CliFixture {
protected:
    // Renders `scene` with the golden settings and `extra` options and compares with `golden`.
    void expectGolden(const std::string& scene, const std::string& extra, const std::string& golden) {
        SCOPED_TRACE(scene + " " + extra);
        const std::string out = path("out.pfm");
        const CliResult r = runCli("render " + sourcePath("scenes/" + scene + "/scene.xml") +
                                   " --res 32x24 --spp 4 --seed 5 --accel bvh -q " + extra + " -o " + out);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const Image expected = readImage(sourcePath("tests/e2e/data/golden/" + golden));
        const Image actual = readImage(out);
        ASSERT_EQ(actual.rgb.size(), expected.rgb.size());
        size_t differing = 0;
        double largest = 0;
        for (size_t i = 0; i < actual.rgb.size(); ++i)
            if (std::memcmp(&actual.rgb[i], &expected.rgb[i], sizeof(float)) != 0) {
                ++differing;
                largest = std::max(largest, double(std::abs(actual.rgb[i] - expected.rgb[i])));
            }
        EXPECT_EQ(differing, 0u) << differing << " of " << actual.rgb.size()
                                 << " values differ from the golden image, by up to " << largest;
    }
};

TEST_F(GoldenImages, PathTracerInBothModes) {
    for (const char* scene : {"cornell-box", "cornell-water", "door-gap"}) {
        expectGolden(scene, "", std::string(scene) + "-path.pfm");
        expectGolden(scene, "--path-mode wavefront", std::string(scene) + "-path.pfm");
    }
}

TEST_F(GoldenImages, Metropolis) {
    for (const char* scene : {"cornell-box", "cornell-water", "door-gap"})
        expectGolden(scene, "--integrator mlt --splat sort --mlt-chains 64 --mlt-bootstrap 1024",
                     std::string(scene) + "-mlt.pfm");
}

}  // namespace
}  // namespace caustica::test
