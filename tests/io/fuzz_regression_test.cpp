// fuzz_regression_test.cpp — minimised inputs found by the libFuzzer targets (fuzz/,
// docs/FUZZING.md) for meshes and images: each must now be refused with one clean
// caustica::Error (scenes found by fuzzing go to tests/io/data/bad instead).
#include <sys/resource.h>

#include <cstring>

#include "caustica/io/image_io.h"
#include "caustica/io/mesh/ply_loader.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

/// Writes a 2x2 EXR with the string attribute spp = "16" to `path` and returns its bytes.
std::string writeExrWithSpp(const std::string& path) {
    Image img(2, 2);
    ImageMetadata md;
    md.entries["spp"] = "16";
    writeImage(path, img, md);
    return readBytes(path);
}

/// `fn` must throw caustica::Error (and nothing else) whose one-line message contains `reason`.
template <class F>
void expectCleanError(F fn, const std::string& reason) {
    try {
        fn();
        ADD_FAILURE() << "no error thrown; expected: " << reason;
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find(reason), std::string::npos) << "reason '" << reason << "' not in: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "unexpected " << typeid(e).name() << ": " << e.what();
    }
}

// fuzz_image found an EXR whose string attribute claims 0x77000002 bytes in a 294-byte file:
// OpenEXR allocated the 2 GB before reading it (out-of-memory under the fuzzer's 2 GB limit).
TEST(FuzzRegression, ExrAttributeLargerThanFile) {
    TempDir dir;
    const std::string good = dir.path("good.exr");
    std::string bytes = writeExrWithSpp(good);
    const std::string tag = std::string("spp\0string\0", 11);
    const size_t at = bytes.find(tag);
    ASSERT_NE(at, std::string::npos);
    const unsigned char size[4] = {0x02, 0x00, 0x00, 0x77};  // little-endian 0x77000002
    std::memcpy(&bytes[at + tag.size()], size, 4);
    const std::string bad = dir.write("attr_size.exr", bytes);
    expectCleanError([&] { readImage(bad); }, "attribute 'spp' claims 1996488706 bytes");
    expectCleanError([&] { readImageMetadata(bad); }, "attribute 'spp' claims 1996488706 bytes");
    // A negative size is refused the same way.
    const unsigned char negative[4] = {0xff, 0xff, 0xff, 0xff};
    std::memcpy(&bytes[at + tag.size()], negative, 4);
    expectCleanError([&] { readImage(dir.write("neg.exr", bytes)); }, "claims -1 bytes");
    // The unpatched file still reads, metadata included.
    EXPECT_EQ(readImage(good).width, 2);
    EXPECT_EQ(readImageMetadata(good).entries.at("spp"), "16");
}

// The same, hidden behind a fixed-size attribute whose size field says 0: OpenEXR reads a box2i's
// 16 bytes whatever the size field says, so the header walk must too (found by fuzz_image).
TEST(FuzzRegression, ExrAttributeLargerThanFileAfterWrongFixedSize) {
    TempDir dir;
    const std::string good = dir.path("good.exr");
    std::string bytes = writeExrWithSpp(good);
    const std::string box = std::string("displayWindow\0box2i\0", 20);
    const std::string spp = std::string("spp\0string\0", 11);
    const size_t atBox = bytes.find(box), atSpp = bytes.find(spp);
    ASSERT_NE(atBox, std::string::npos);
    ASSERT_NE(atSpp, std::string::npos);
    ASSERT_LT(atBox, atSpp);
    const unsigned char zero[4] = {0, 0, 0, 0};
    std::memcpy(&bytes[atBox + box.size()], zero, 4);
    const unsigned char size[4] = {0x02, 0x00, 0x00, 0x30};  // 0x30000002
    std::memcpy(&bytes[atSpp + spp.size()], size, 4);
    const std::string bad = dir.write("fixed_size.exr", bytes);
    expectCleanError([&] { readImage(bad); }, "attribute 'spp' claims 805306370 bytes");
    expectCleanError([&] { readImageMetadata(bad); }, "attribute 'spp' claims 805306370 bytes");
}

// fuzz_image found a 591-byte EXR whose data window is 8847364 x 513 pixels: OpenEXR sized its
// line buffers by it on opening the file, before readImage's size check (a 5 s timeout under
// ASan); readImageMetadata had no size check at all. The header walk now checks the window, the
// chunk offset table and the size of one chunk before OpenEXR opens the file.
TEST(FuzzRegression, ExrDataWindowCheckedBeforeOpenExrSizesBuffersByIt) {
    TempDir dir;
    const std::string good = dir.path("good.exr");
    std::string bytes = writeExrWithSpp(good);
    const std::string tag = std::string("dataWindow\0box2i\0\x10\0\0\0", 21);
    const size_t at = bytes.find(tag);
    ASSERT_NE(at, std::string::npos);
    auto withWindow = [&](int32_t maxX, int32_t maxY) {  // (0, 0) to (maxX, maxY)
        std::string b = bytes;
        std::memcpy(&b[at + tag.size() + 8], &maxX, 4);  // little-endian, like EXR
        std::memcpy(&b[at + tag.size() + 12], &maxY, 4);
        return b;
    };
    const std::string wide = dir.write("wide.exr", withWindow(8847363, 512));
    expectCleanError([&] { readImage(wide); }, "absurd image size 8847364 x 513");
    expectCleanError([&] { readImageMetadata(wide); }, "absurd image size 8847364 x 513");
    // A window of allowed size whose table of chunk offsets cannot be in the file.
    const std::string tall = dir.write("tall.exr", withWindow(0, (1 << 24) - 1));
    expectCleanError([&] { readImage(tall); }, "chunk offsets, more than the file holds");
    expectCleanError([&] { readImageMetadata(tall); }, "chunk offsets, more than the file holds");
    // Found next: a window within kMaxImagePixels but 8386820 pixels wide, for which OpenEXR's
    // ZIP decompressor wanted 16 lines (here of 3 floats): 1.5 GiB for a 3-row image.
    const std::string wideChunk = dir.write("wide_chunk.exr", withWindow(8386819, 2));
    const std::string chunk = "(16 scan lines 8386820 pixels wide) would take 1535 MiB";
    expectCleanError([&] { readImage(wideChunk); }, chunk);
    expectCleanError([&] { readImageMetadata(wideChunk); }, chunk);
    // Found last: a 262148 x 549 window (1.7 GB of floats) whose chunks are not in the file;
    // readImage allocated the image before finding that out. Padding makes the offsets fit.
    auto peakRssKb = [] {
        rusage u{};
        getrusage(RUSAGE_SELF, &u);
        return long(u.ru_maxrss);  // kilobytes on Linux
    };
    const std::string missing =
        dir.write("missing_chunks.exr", withWindow(262147, 548) + std::string(512, '\0'));
    const long before = peakRssKb();
    expectCleanError([&] { readImage(missing); }, "truncated");
    EXPECT_LT(peakRssKb() - before, 256 * 1024) << "peak RSS grew by over 256 MB";
    EXPECT_EQ(readImage(good).width, 2);
}

// fuzz_image found a 43-byte PFM whose height is -5.2e29: converting it to an integer was
// undefined behaviour (UBSan), as only sizes above 1e9 were refused.
TEST(FuzzRegression, PfmHugeNegativeHeight) {
    TempDir dir;
    const std::string pfm("PF\n4 -522222222222222222222222222222\n1.0\n\0\xcc", 43);
    const std::string bad = dir.write("negative.pfm", pfm);
    expectCleanError([&] { readImage(bad); }, "corrupt header: bad image size");
}

// fuzz_image found a 357-byte JPEG whose scan uses AC Huffman table 0, which it never defines:
// stb decoded with the garbage its malloc held and an assertion in stbi__jpeg_huff_decode aborted
// the process. Here an 8 x 8 grey JPEG built by hand, with and without its tables; then the
// scan-length and table-size checks that came with it.
TEST(FuzzRegression, JpegScanUsingUndefinedHuffmanTable) {
    TempDir dir;
    auto segment = [](unsigned char marker, const std::string& body) {
        const size_t n = body.size() + 2;
        return std::string{'\xff', char(marker), char(n >> 8), char(n & 255)} + body;
    };
    const std::string soi("\xff\xd8", 2), eoi("\xff\xd9", 2);
    const std::string dqt = segment(0xdb, std::string(1, '\0') + std::string(64, '\1'));
    const std::string sof = segment(0xc0, std::string("\x08\0\x08\0\x08\x01\x01\x11\0", 9));
    // One code of length 1 for symbol 0: DC difference 0, or AC end of block.
    auto dht = [&](char tableClass) {
        return segment(0xc4, std::string(1, tableClass) + '\1' + std::string(15, '\0') + '\0');
    };
    const std::string sos = segment(0xda, std::string("\x01\x01\0\0\x3f\0", 6)) + '\x3f';
    const std::string good =
        dir.write("good.jpg", soi + dqt + sof + dht(0) + dht(0x10) + sos + eoi);
    EXPECT_EQ(readImage(good).width, 8);
    const std::string noAc = dir.write("no_ac.jpg", soi + dqt + sof + dht(0) + sos + eoi);
    expectCleanError([&] { readImage(noAc); }, "scan uses AC Huffman table 0, which no DHT");
    const std::string noDq = dir.write("no_dqt.jpg", soi + sof + dht(0) + dht(0x10) + sos + eoi);
    expectCleanError([&] { readImage(noDq); }, "scan uses quantisation table 0, which no DQT");
    // Found next: a 13156 x 4214 image in 22 bytes of scan data, which stb decoded as zeros.
    // A baseline block takes at least 2 bits: the 1 byte of data holds 4 blocks, not 1024.
    const std::string sof256 =
        segment(0xc0, std::string("\x08\x01\0\x01\0\x01\x01\x11\0", 9));  // 256 x 256
    const std::string big =
        dir.write("big.jpg", soi + dqt + sof256 + dht(0) + dht(0x10) + sos + eoi);
    expectCleanError([&] { readImage(big); }, "scan of 1024 blocks holds 1 bytes");
    // More symbols than the 256 stb has room for (255 + 255 codes of lengths 15 and 16).
    const std::string huge =
        segment(0xc4, std::string(15, '\0') + "\xff\xff" + std::string(510, 'x'));
    expectCleanError([&] { readImage(dir.write("huge.jpg", soi + huge + eoi)); },
                     "Huffman table with 510 symbols (at most 256)");
}

// fuzz_ply found a binary PLY whose element 'xte' promises 2e9 records without properties: the
// loader read them one by one, 0 bytes each (a timeout). With 1e18 of them it would never end.
TEST(FuzzRegression, PlyElementWithoutPropertiesAndAHugeCount) {
    TempDir dir;
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement xte 1000000000000000000\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int32_t tri[3] = {0, 1, 2};
    std::string body(reinterpret_cast<const char*>(xyz), sizeof xyz);
    body += '\3' + std::string(reinterpret_cast<const char*>(tri), sizeof tri);
    EXPECT_EQ(meshio::loadPly(dir.write("binary.ply", header + body)).triangles.size(), 1u);
    // In ASCII such records are empty lines, and the next element's lines are its own.
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement xte 2\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n\n\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    EXPECT_EQ(meshio::loadPly(dir.write("ascii.ply", ascii)).triangles.size(), 1u);
}

// fuzz_image found an 85-byte PNG (no IDAT) whose IHDR claims 516 x 262147 pixels: readPng
// allocated and cleared the 1.6 GB image before stb refused the data (a 5 s timeout under ASan).
TEST(FuzzRegression, PngHeaderClaimingAHugeImage) {
    TempDir dir;
    const std::string png(
        "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x02\x04\x00\x04"
        "\x00\x03\x08\x02\x00\x00\x00\x3b\x96\x38\x91\x00\x00\x00\x06\x74\x45\x58\xff\xff\xff\xff"
        "\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff"
        "\xff\xff\xff\xcc\xff\xff\xff\xff\xff\xff\xc2\x50\xc3\x00\x07\x2c\x42\x60\x82",
        85);
    const std::string bad = dir.write("huge_header.png", png);
    expectCleanError([&] { readImage(bad); }, "corrupt or truncated data");
}

// fuzz_image found a 103-byte PNG whose last chunk header claims 0x6000001f bytes of IDAT: stb
// allocated 2 GiB for the chunk before finding the file short (out-of-memory under the fuzzer).
TEST(FuzzRegression, PngChunkLongerThanFile) {
    TempDir dir;
    const std::string good = dir.path("good.png");
    writeImage(good, Image(2, 2));
    const std::string bytes = readBytes(good);
    ASSERT_EQ(bytes.compare(12, 4, "IHDR"), 0);
    // Signature (8 bytes) and IHDR (25 bytes), then an IDAT claiming far more than follows.
    auto withIdatOfLength = [&](const std::string& length) {
        return bytes.substr(0, 33) + length + "IDAT" + std::string("\x78\x01\x00\x00", 4);
    };
    const std::string huge =
        dir.write("huge_idat.png", withIdatOfLength(std::string("\x7f\xff\x00\x00", 4)));
    const std::string reason = "PNG chunk 'IDAT' length 2147418112";
    expectCleanError([&] { readImage(huge); }, reason);
    expectCleanError([&] { readImageMetadata(huge); }, reason);
    // Beyond PNG's own limit of 2^31 - 1.
    expectCleanError(
        [&] { readImage(dir.write("over.png", withIdatOfLength("\xff\xff\xff\xf0"))); },
        "PNG chunk 'IDAT' length 4294967280");
    // The unpatched file still reads.
    EXPECT_EQ(readImage(good).width, 2);
}

}  // namespace
}  // namespace caustica::test
