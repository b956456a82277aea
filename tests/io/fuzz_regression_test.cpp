// fuzz_regression_test.cpp — minimised inputs found by the libFuzzer targets (fuzz/,
// docs/FUZZING.md) for meshes and images: each must now be refused with one clean
// caustica::Error (scenes found by fuzzing go to tests/io/data/bad instead).
#include <cstring>

#include "caustica/io/image_io.h"
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
