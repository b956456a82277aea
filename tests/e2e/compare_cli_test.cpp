// `caustica compare` refuses images that cannot be compared: NaN or infinite pixels in the image,
// the reference or the reference's variance, and truncated EXR / PFM files. Each is one error
// line naming the file, a non-zero exit, and no figure.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "caustica/io/image_io.h"
#include "cli_helpers.h"

namespace caustica::test {
namespace {

class CompareCli : public CliFixture {
protected:
    /// A copy of `name` cut to its first `keep` bytes, as "cut_NAME".
    std::string cutCopy(const std::string& name, size_t keep) const {
        std::ifstream in(path(name), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
        std::ofstream(path("cut_" + name), std::ios::binary) << bytes.substr(0, keep);
        return "cut_" + name;
    }

    void SetUp() override {
        CliFixture::SetUp();
        Image image(4, 4);
        for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = 0.1f * float(i % 7);
        for (const char* name : {"good.exr", "good.pfm", "var.exr"}) writeImage(path(name), image);
        const float nan = std::numeric_limits<float>::quiet_NaN();
        image.set(1, 2, Spectrum(nan, 0.5f, nan));  // 2 pixels, 3 values
        image.rgb[0] = std::numeric_limits<float>::infinity();
        for (const char* name : {"nan.exr", "nan.pfm"}) writeImage(path(name), image);
    }

    // The command fails with one line "caustica: error: FILE: ..." holding `reason`, and prints no
    // metric.
    void expectRefused(const std::string& args, const std::string& file,
                       const std::string& reason) {
        const CliResult r = runCli("compare " + args);
        EXPECT_NE(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("caustica: error: " + path(file) + ": "), std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find(reason), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        for (const char* figure : {"MSE", "mse"})
            EXPECT_EQ(r.output.find(figure), std::string::npos) << r.output;
    }
};

TEST_F(CompareCli, ComparableImagesGiveFigures) {
    const CliResult r = runCli("compare " + path("good.exr") + " " + path("good.pfm") +
                               " --ref-var " + path("var.exr") + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("\"mse\": 0,"), std::string::npos) << r.output;
}

TEST_F(CompareCli, NonFinitePixelsAreRefusedNamingTheFileAndHowMany) {
    const std::string notFinite = "2 of 16 pixels are not finite (3 NaN or infinite values)";
    expectRefused(path("nan.exr") + " " + path("good.exr"), "nan.exr", notFinite);
    expectRefused(path("good.exr") + " " + path("nan.pfm") + " --json", "nan.pfm", notFinite);
    expectRefused(path("good.exr") + " " + path("good.exr") + " --ref-var " + path("nan.exr"),
                  "nan.exr", notFinite);
}

TEST_F(CompareCli, TruncatedFilesAreRefused) {
    for (const std::string name : {"good.exr", "good.pfm"}) {
        const size_t size = std::filesystem::file_size(path(name));
        for (size_t keep : {size_t(10), size / 2, size - 1}) {
            SCOPED_TRACE(name + " cut to " + std::to_string(keep));
            const std::string cut = cutCopy(name, keep);
            expectRefused(path(cut) + " " + path("good.exr"), cut, "");
            expectRefused(path("good.exr") + " " + path(cut), cut, "");
        }
    }
    // The last pixels missing: refused as truncated, not read as zeros.
    expectRefused(
        path(cutCopy("good.exr", size_t(std::filesystem::file_size(path("good.exr")) - 1))) + " " +
            path("good.exr"),
        "cut_good.exr", "truncated");
    expectRefused(
        path("good.exr") + " " +
            path(cutCopy("good.pfm", size_t(std::filesystem::file_size(path("good.pfm")) - 1))),
        "cut_good.pfm", "truncated data");
}

}  // namespace
}  // namespace caustica::test
