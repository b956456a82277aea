// image_formats_test.cpp — JPEG and Radiance HDR reading (readImage), the raw option for
// sRGB-encoded formats, and their errors (wrong signature, truncated data, writing refused).
#include <gtest/gtest.h>

#include <stb_image_write.h>

#include <filesystem>
#include <string>
#include <vector>

#include "caustica/io/image_io.h"
#include "caustica/util/error.h"
#include "scene_test_util.h"

namespace caustica {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::writeBytes;

class ImageFormats : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return dir_.path(name); }

    /// An 8 x 8 JPEG of one flat colour (JPEG keeps a flat block almost exact).
    std::string writeJpeg(const std::string& name, unsigned char r, unsigned char g,
                          unsigned char b, int quality = 100) {
        std::vector<unsigned char> px;
        for (int i = 0; i < 8 * 8; ++i) px.insert(px.end(), {r, g, b});
        const std::string p = path(name);
        EXPECT_TRUE(stbi_write_jpg(p.c_str(), 8, 8, 3, px.data(), quality));
        return p;
    }

    /// Expects readImage(p) to throw a caustica::Error naming the file and `reason`.
    static void expectReadError(const std::string& p, const std::string& reason) {
        try {
            readImage(p);
            ADD_FAILURE() << "no error for " << p;
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(p), std::string::npos) << msg;
            EXPECT_NE(msg.find(reason), std::string::npos) << msg;
        }
    }

    test::TempDir dir_;  // fresh for each test
};

TEST_F(ImageFormats, JpegIsDecodedFromSrgb) {
    for (const char* name : {"flat.jpg", "flat.JPEG"}) {
        const std::string p = writeJpeg(name, 200, 100, 30);
        ImageFileInfo info;
        const Image img = readImage(p, ImageReadOptions{}, &info);
        ASSERT_EQ(img.width, 8);
        ASSERT_EQ(img.height, 8);
        EXPECT_EQ(info.bitsPerChannel, 8);
        const Spectrum c = img.at(3, 5);
        EXPECT_NEAR(c.r, srgbToLinear(200 / 255.0f), 0.01f);
        EXPECT_NEAR(c.g, srgbToLinear(100 / 255.0f), 0.01f);
        EXPECT_NEAR(c.b, srgbToLinear(30 / 255.0f), 0.01f);
        ImageReadOptions raw;
        raw.raw = true;
        const Spectrum r = readImage(p, raw).at(3, 5);
        EXPECT_NEAR(r.r, 200 / 255.0f, 0.02f);
        EXPECT_NEAR(r.b, 30 / 255.0f, 0.02f);
        EXPECT_TRUE(readImageMetadata(p).entries.empty());
    }
}

TEST_F(ImageFormats, GreyJpegIsReplicated) {
    std::vector<unsigned char> px(16 * 8, 90);
    const std::string p = path("grey.jpg");
    ASSERT_TRUE(stbi_write_jpg(p.c_str(), 16, 8, 1, px.data(), 100));
    const Image img = readImage(p);
    EXPECT_EQ(img.width, 16);
    const Spectrum c = img.at(9, 2);
    EXPECT_NEAR(c.r, srgbToLinear(90 / 255.0f), 0.01f);
    EXPECT_EQ(c.r, c.g);
    EXPECT_EQ(c.g, c.b);
}

TEST_F(ImageFormats, RadianceHdrIsLinear) {
    std::vector<float> px;
    for (int i = 0; i < 6; ++i) px.insert(px.end(), {0.25f * float(i), 3.0f, 1000.0f});
    const std::string p = path("sky.hdr");
    ASSERT_TRUE(stbi_write_hdr(p.c_str(), 3, 2, 3, px.data()));
    ImageFileInfo info;
    ImageReadOptions raw;
    raw.raw = true;  // no effect on float formats
    const Image img = readImage(p, raw, &info);
    ASSERT_EQ(img.width, 3);
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(info.bitsPerChannel, 32);
    for (int i = 0; i < 6; ++i) {
        const Spectrum c = img.at(i % 3, i / 3);
        // RGBE keeps 8 mantissa bits per channel relative to the largest one.
        EXPECT_NEAR(c.b, 1000.0f, 4.0f);
        EXPECT_NEAR(c.g, 3.0f, 4.0f);
    }
    EXPECT_EQ(readImage(p).at(1, 0).b, img.at(1, 0).b);
}

TEST_F(ImageFormats, Errors) {
    // A PNG named .jpg and a JPEG named .hdr: the signature decides, not the name alone.
    Image small(2, 2);
    writeImage(path("png.png"), small);
    fs::copy_file(path("png.png"), path("png.jpg"));
    expectReadError(path("png.jpg"), "not a JPEG file");
    const std::string jpg = writeJpeg("real.jpg", 10, 20, 30);
    fs::copy_file(jpg, path("jpeg.hdr"));
    expectReadError(path("jpeg.hdr"), "not a Radiance HDR file");
    // Truncated files.
    const std::string bytes = readBytes(jpg);
    writeBytes(path("cut.jpg"), bytes.substr(0, bytes.size() / 3));
    expectReadError(path("cut.jpg"), "corrupt");
    std::vector<float> px(3 * 64 * 64, 0.5f);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 97) * 0.37f;
    ASSERT_TRUE(stbi_write_hdr(path("big.hdr").c_str(), 64, 64, 3, px.data()));
    const std::string hdr = readBytes(path("big.hdr"));
    writeBytes(path("cut.hdr"), hdr.substr(0, hdr.size() / 2));
    expectReadError(path("cut.hdr"), "truncated data");
    writeBytes(path("header.hdr"), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 99999 +X 99999\n");
    expectReadError(path("header.hdr"), "corrupt");
    expectReadError(path("missing.jpg"), "cannot open");
    // Writing JPEG / HDR is not offered.
    try {
        writeImage(path("out.jpg"), small);
        ADD_FAILURE() << "writing a .jpg succeeded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not supported"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path("out.jpg")));
}

}  // namespace
}  // namespace caustica
