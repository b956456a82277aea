// exr_truncation_test.cpp — readImage's check that every chunk of an EXR lies within the file:
// scan-line files of every compression, tiled files of every level mode and multi-part files
// read back whole, and the same files cut short anywhere are refused, naming the file (an
// uncompressed file cut inside its pixels would otherwise be read with zeros by some OpenEXRs).
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include <functional>
#include <random>
#include <string>
#include <vector>

#include "caustica/io/image_io.h"
#include "caustica/util/error.h"
#include "scene_test_util.h"

namespace caustica {
namespace {

constexpr int kWidth = 7, kHeight = 300;  // more rows than the largest chunk (DWAB: 256)

/// Random float RGB pixels, row-major, and a frame buffer over them.
struct Pixels {
    std::vector<float> rgb = std::vector<float>(3 * kWidth * kHeight);
    Pixels() {
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (float& v : rgb) v = u(rng);
    }
    Imf::FrameBuffer frameBuffer() {
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(rgb.data());
        const size_t xs = 3 * sizeof(float), ys = xs * kWidth;
        for (int c = 0; c < 3; ++c)
            fb.insert(std::string(1, "RGB"[c]), Imf::Slice(Imf::FLOAT, base + 4 * c, xs, ys));
        return fb;
    }
};

Imf::Header rgbHeader(Imf::Compression compression) {
    Imf::Header header(kWidth, kHeight);
    header.compression() = compression;
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    return header;
}

void writeScanLines(const std::string& path, Imf::Compression compression) {
    Pixels pixels;
    Imf::OutputFile file(path.c_str(), rgbHeader(compression));
    file.setFrameBuffer(pixels.frameBuffer());
    file.writePixels(kHeight);
}

void writeTiles(const std::string& path, Imf::LevelMode mode, Imf::LevelRoundingMode rounding) {
    Pixels pixels;
    Imf::Header header = rgbHeader(Imf::NO_COMPRESSION);
    header.setTileDescription(Imf::TileDescription(4, 32, mode, rounding));
    Imf::TiledOutputFile file(path.c_str(), header);
    file.setFrameBuffer(pixels.frameBuffer());  // smaller levels read the top-left corner
    for (int ly = 0; ly < file.numYLevels(); ++ly)
        for (int lx = 0; lx < file.numXLevels(); ++lx)
            if (lx == ly || mode == Imf::RIPMAP_LEVELS)
                file.writeTiles(0, file.numXTiles(lx) - 1, 0, file.numYTiles(ly) - 1, lx, ly);
}

void writeTwoParts(const std::string& path) {
    Pixels pixels;
    std::vector<Imf::Header> headers(2, rgbHeader(Imf::NO_COMPRESSION));
    for (int i = 0; i < 2; ++i) {
        headers[size_t(i)].setName("part" + std::to_string(i));
        headers[size_t(i)].setType(Imf::SCANLINEIMAGE);
    }
    Imf::MultiPartOutputFile file(path.c_str(), headers.data(), 2);
    for (int i = 0; i < 2; ++i) {
        Imf::OutputPart part(file, i);
        part.setFrameBuffer(pixels.frameBuffer());
        part.writePixels(kHeight);
    }
}

/// Every layout this test writes: (file name, writer).
std::vector<std::pair<std::string, std::function<void(const std::string&)>>> layouts() {
    std::vector<std::pair<std::string, std::function<void(const std::string&)>>> all;
    const std::pair<const char*, Imf::Compression> kCompressions[] = {
        {"none", Imf::NO_COMPRESSION},   {"rle", Imf::RLE_COMPRESSION},
        {"zips", Imf::ZIPS_COMPRESSION}, {"zip", Imf::ZIP_COMPRESSION},
        {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
        {"b44", Imf::B44_COMPRESSION},   {"b44a", Imf::B44A_COMPRESSION},
        {"dwaa", Imf::DWAA_COMPRESSION}, {"dwab", Imf::DWAB_COMPRESSION}};
    for (const auto& [name, c] : kCompressions)
        all.push_back({std::string("lines_") + name + ".exr",
                       [c = c](const std::string& p) { writeScanLines(p, c); }});
    all.push_back({"tiles_one.exr",
                   [](const std::string& p) { writeTiles(p, Imf::ONE_LEVEL, Imf::ROUND_DOWN); }});
    all.push_back({"tiles_mip_down.exr", [](const std::string& p) {
                       writeTiles(p, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN);
                   }});
    all.push_back({"tiles_mip_up.exr",
                   [](const std::string& p) { writeTiles(p, Imf::MIPMAP_LEVELS, Imf::ROUND_UP); }});
    all.push_back({"tiles_rip.exr", [](const std::string& p) {
                       writeTiles(p, Imf::RIPMAP_LEVELS, Imf::ROUND_DOWN);
                   }});
    all.push_back({"two_parts.exr", writeTwoParts});
    return all;
}

TEST(ExrTruncation, EveryLayoutReadsBackWhole) {
    test::TempDir dir;
    const Pixels expected;
    for (const auto& [name, write] : layouts()) {
        SCOPED_TRACE(name);
        const std::string p = dir.path(name);
        write(p);
        Image image;
        ASSERT_NO_THROW(image = readImage(p));
        ASSERT_EQ(image.width, kWidth);
        ASSERT_EQ(image.height, kHeight);
        const bool lossy =
            name.find("pxr24") != std::string::npos || name.find("dwa") != std::string::npos;
        if (!lossy) {
            EXPECT_EQ(image.rgb, expected.rgb);
        }
    }
}

// Cut in its header or offset table, a file is refused by whichever check meets the cut first;
// cut in its pixels (here past the first half), by the chunk check, which says "truncated".
TEST(ExrTruncation, CutShortIsRefusedWhateverTheLayout) {
    test::TempDir dir;
    for (const auto& [name, write] : layouts()) {
        const std::string p = dir.path(name);
        write(p);
        const std::string bytes = test::readBytes(p);
        std::vector<size_t> cuts = {0, 8, 20, 100, bytes.size() / 4, bytes.size() - 1};
        for (int k = 10; k < 20; ++k) cuts.push_back(bytes.size() * size_t(k) / 20);
        for (size_t keep : cuts) {
            SCOPED_TRACE(name + " cut to " + std::to_string(keep) + " of " +
                         std::to_string(bytes.size()));
            test::writeBytes(p, bytes.substr(0, keep));
            try {
                readImage(p);
                ADD_FAILURE() << "no error";
            } catch (const Error& e) {
                EXPECT_EQ(e.file(), p);
                if (keep >= bytes.size() / 2) {
                    EXPECT_NE(e.reason().find("truncated"), std::string::npos) << e.what();
                }
            }
        }
    }
}

// A chunk offset pointing outside the file (a damaged table, not a cut) is refused too.
TEST(ExrTruncation, ChunkOffsetPastTheEndIsRefused) {
    test::TempDir dir;
    const std::string p = dir.path("offset.exr");
    writeScanLines(p, Imf::NO_COMPRESSION);
    std::string bytes = test::readBytes(p);
    // The last of the 300 offsets (8 bytes each) ends right before the first chunk.
    const size_t firstChunk = bytes.size() - size_t(kHeight) * (8 + 3 * 4 * kWidth);
    bytes[firstChunk - 2] = 0x40;  // a high byte of the last offset
    test::writeBytes(p, bytes);
    try {
        readImage(p);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(e.reason().find("chunk 299 of 300 is missing"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace caustica
