// image_io_test.cpp — EXR / PFM / PNG round trips, half and grey EXR input, 16-bit PNG input,
// and errors (missing, corrupt, truncated, absurd) that name the file.
#include <gtest/gtest.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "caustica/io/image_io.h"
#include "caustica/util/error.h"
#include "scene_test_util.h"

namespace caustica {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::writeBytes;

class ImageIo : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return dir_.path(name); }

    static Image randomImage(int w, int h, float lo, float hi, uint32_t seed) {
        Image img(w, h);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(lo, hi);
        for (float& v : img.rgb) v = u(rng);
        return img;
    }
    // Expects readImage(p) to throw a caustica::Error naming p.
    static void expectReadError(const std::string& p) {
        try {
            readImage(p);
            ADD_FAILURE() << "no error reading " << p;
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), p);
            EXPECT_FALSE(e.reason().empty());
        }
    }

    test::TempDir dir_;  // fresh for each test
};

TEST_F(ImageIo, ExrFloatRoundTripIsExactWithMetadata) {
    Image img = randomImage(37, 23, -5.0f, 1e4f, 1);
    img.rgb[4] = 1e-30f;
    img.rgb[7] = 3.4e38f;
    ImageMetadata meta;
    meta.entries = {{"spp", "1024"}, {"integrator", "path"}, {"renderTime", "12.5 s"}};
    const std::string p = path("float.exr");
    writeImage(p, img, meta);
    const Image back = readImage(p);
    ASSERT_EQ(back.width, 37);
    ASSERT_EQ(back.height, 23);
    EXPECT_EQ(std::memcmp(back.rgb.data(), img.rgb.data(), img.rgb.size() * 4), 0);
    const ImageMetadata m = readImageMetadata(p);
    for (const auto& [k, v] : meta.entries) EXPECT_EQ(m.entries.at(k), v) << k;
    EXPECT_FALSE(fs::exists(p + ".partial.exr"));
    // float32 R, G, B with ZIP compression, as the format contract says.
    Imf::InputFile file(p.c_str());
    EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
    for (const char* c : {"R", "G", "B"}) {
        ASSERT_NE(file.header().channels().findChannel(c), nullptr) << c;
        EXPECT_EQ(file.header().channels().findChannel(c)->type, Imf::FLOAT) << c;
    }
}

TEST_F(ImageIo, ExrRefusesReservedMetadataKeys) {
    ImageMetadata meta;
    meta.entries = {{"compression", "none"}};
    const std::string p = path("reserved.exr");
    EXPECT_THROW(writeImage(p, Image(2, 2), meta), Error);
    EXPECT_FALSE(fs::exists(p));
}

// Writes an EXR with the given half channels (all set to value(x, y, channel index)).
template <class F>
void writeHalfExr(const std::string& p, int w, int h, const std::vector<std::string>& names,
                  F value) {
    Imf::Header header(w, h);
    for (const auto& n : names) header.channels().insert(n, Imf::Channel(Imf::HALF));
    std::vector<std::vector<half>> planes(names.size(), std::vector<half>(size_t(w) * h));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) planes[c][size_t(y) * w + x] = half(value(x, y, int(c)));
        fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(planes[c].data()),
                                       sizeof(half), sizeof(half) * w));
    }
    Imf::OutputFile file(p.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
}

TEST_F(ImageIo, ReadsHalfRgbaAndGreyExr) {
    // Values exactly representable in half.
    auto value = [](int x, int y, int c) { return 0.25f * float(x) + 8.0f * float(y) + float(c); };
    const std::string rgba = path("half_rgba.exr");
    writeHalfExr(rgba, 5, 3, {"R", "G", "B", "A"}, value);
    const Image img = readImage(rgba);
    ASSERT_EQ(img.width, 5);
    ASSERT_EQ(img.height, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y)[c], value(x, y, c));

    const std::string grey = path("half_y.exr");
    writeHalfExr(grey, 4, 2, {"Y"}, value);
    const Image g = readImage(grey);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(g.at(x, y)[c], value(x, y, 0));

    const std::string depth = path("depth_only.exr");
    writeHalfExr(depth, 2, 2, {"Z"}, value);
    expectReadError(depth);
}

TEST_F(ImageIo, PfmRoundTripIsExactAndBottomRowFirst) {
    const Image img = randomImage(9, 4, -1.0f, 100.0f, 2);
    const std::string p = path("img.pfm");
    writeImage(p, img);
    const Image back = readImage(p);
    ASSERT_TRUE(back.sameSize(img));
    EXPECT_EQ(std::memcmp(back.rgb.data(), img.rgb.data(), img.rgb.size() * 4), 0);
    const std::string bytes = readBytes(p);
    const std::string header = "PF\n9 4\n-1.0\n";
    ASSERT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(bytes.size(), header.size() + 9 * 4 * 3 * 4);
    float first;
    std::memcpy(&first, bytes.data() + header.size(), 4);
    EXPECT_EQ(first, img.at(0, 3).r);  // the file starts with the bottom-left pixel
}

TEST_F(ImageIo, ReadsGreyAndBigEndianPfm) {
    // "Pf" grey, big-endian (positive scale 1), 2 x 2: rows bottom to top.
    std::string bytes = "Pf\n2 2\n1.0\n";
    for (float v : {3.0f, 4.0f, 1.0f, 2.0f}) {  // bottom row (3, 4), top row (1, 2)
        uint32_t u;
        std::memcpy(&u, &v, 4);
        for (int s = 24; s >= 0; s -= 8) bytes += char((u >> s) & 0xff);
    }
    const std::string p = path("grey.pfm");
    writeBytes(p, bytes);
    const Image img = readImage(p);
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 0).g, 1.0f);
    EXPECT_EQ(img.at(1, 0).b, 2.0f);
    EXPECT_EQ(img.at(0, 1).r, 3.0f);
    EXPECT_EQ(img.at(1, 1).r, 4.0f);
}

TEST_F(ImageIo, PngWithinSrgbQuantisation) {
    Image img = randomImage(17, 11, 0.0f, 1.0f, 3);
    img.rgb[0] = 2.5f;   // clamps to 1
    img.rgb[1] = -1.0f;  // clamps to 0
    ImageMetadata meta;
    meta.entries = {{"spp", "64"}, {"Software", "caustica"}};
    const std::string p = path("img.PNG");
    writeImage(p, img, meta);
    const Image back = readImage(p);
    ASSERT_TRUE(back.sameSize(img));
    EXPECT_EQ(back.rgb[0], 1.0f);
    EXPECT_EQ(back.rgb[1], 0.0f);
    for (size_t i = 2; i < img.rgb.size(); ++i)  // half a code value in sRGB space
        EXPECT_NEAR(linearToSrgb(back.rgb[i]), linearToSrgb(img.rgb[i]), 0.5 / 255 + 1e-6) << i;
    EXPECT_EQ(readImageMetadata(p).entries, meta.entries);
}

// A minimal valid PNG: 16-bit RGB, uncompressed deflate (stored block).
std::string png16(int w, int h, const std::vector<uint16_t>& rgb) {
    auto be32 = [](std::string& s, uint32_t v) {
        for (int k = 24; k >= 0; k -= 8) s += char((v >> k) & 0xff);
    };
    auto crc = [](const std::string& d) {
        uint32_t c = 0xffffffffu;
        for (unsigned char b : d) {
            c ^= b;
            for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
        }
        return ~c;
    };
    auto chunk = [&](std::string& out, const std::string& typeAndData) {
        be32(out, uint32_t(typeAndData.size() - 4));
        out += typeAndData;
        be32(out, crc(typeAndData));
    };
    std::string raw;
    for (int y = 0; y < h; ++y) {
        raw += char(0);  // filter: none
        for (int i = 0; i < 3 * w; ++i) {
            const uint16_t v = rgb[size_t(y) * 3 * w + i];
            raw += char(v >> 8);
            raw += char(v & 0xff);
        }
    }
    uint32_t a = 1, b = 0;  // adler32
    for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
    std::string z = "\x78\x01";
    z += char(1);  // final stored block
    z += char(raw.size() & 0xff), z += char(raw.size() >> 8);
    z += char(~raw.size() & 0xff), z += char((~raw.size() >> 8) & 0xff);
    z += raw;
    be32(z, (b << 16) | a);
    std::string png = "\x89PNG\r\n\x1a\n";
    std::string ihdr = "IHDR";
    be32(ihdr, uint32_t(w));
    be32(ihdr, uint32_t(h));
    // 16 bits, RGB, deflate, no filter, no interlace
    ihdr += std::string("\x10\x02\x00\x00\x00", 5);
    chunk(png, ihdr);
    chunk(png, "IDAT" + z);
    chunk(png, "IEND");
    return png;
}

TEST_F(ImageIo, Reads16BitPng) {
    const std::vector<uint16_t> values = {0, 65535, 32768, 1000, 20000, 50000};
    const std::string p = path("deep.png");
    writeBytes(p, png16(2, 1, values));
    const Image img = readImage(p);
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 1);
    for (size_t i = 0; i < values.size(); ++i)
        EXPECT_NEAR(img.rgb[i], srgbToLinear(float(values[i]) / 65535.0f), 1e-7) << i;
}

TEST_F(ImageIo, MissingFilesAndUnknownExtensions) {
    for (const char* name : {"none.exr", "none.pfm", "none.png"}) expectReadError(path(name));
    expectReadError(path("image.tiff"));
    EXPECT_THROW(readImageMetadata(path("none.exr")), Error);
    EXPECT_THROW(writeImage(path("out.jpg"), Image(2, 2)), Error);
    EXPECT_THROW(writeImage(path("no_such_dir/out.exr"), Image(2, 2)), Error);
    EXPECT_THROW(writeImage(path("empty.exr"), Image()), Error);
}

TEST_F(ImageIo, CorruptFiles) {
    const std::string garbage = "this is not an image file at all, just some text\n";
    for (const char* name : {"bad.exr", "bad.pfm", "bad.png"}) {
        writeBytes(path(name), garbage);
        expectReadError(path(name));
    }
    writeBytes(path("empty.exr"), "");
    expectReadError(path("empty.exr"));
    writeBytes(path("absurd.pfm"), "PF\n100000000 100000000\n-1.0\n0000");
    expectReadError(path("absurd.pfm"));
    writeBytes(path("negative.pfm"), "PF\n-3 2\n-1.0\n0000");
    expectReadError(path("negative.pfm"));
    writeBytes(path("noscale.pfm"), "PF\n3 2\nabc\n0000");
    expectReadError(path("noscale.pfm"));
}

TEST_F(ImageIo, TruncatedFiles) {
    const Image img = randomImage(64, 48, 0.0f, 1.0f, 4);
    for (const char* name : {"t.exr", "t.pfm", "t.png"}) {
        const std::string p = path(name);
        writeImage(p, img);
        const std::string bytes = readBytes(p);
        for (size_t keep : {bytes.size() / 2, bytes.size() - 16, size_t(20)}) {
            writeBytes(p, bytes.substr(0, keep));
            expectReadError(p);
        }
    }
}

}  // namespace
}  // namespace caustica
