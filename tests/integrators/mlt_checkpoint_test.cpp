// mlt_checkpoint_test.cpp — the MLT checkpoint shared by both drivers (mlt_checkpoint.h) on host
// data: a written checkpoint reads back field for field; keys, sizes and damage are refused by
// name; the store transposition between the GPU's dimension-major and the file's chain-major
// layout. Whole renders saved and resumed: tests/e2e/mlt_test.cpp (CPU), tests/gpu (GPU).
#include <gtest/gtest.h>

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "caustica/integrators/mlt/mlt_checkpoint.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

MltCheckpoint someCheckpoint() {
    MltCheckpoint c;
    c.stats.iterations = 7;
    c.stats.proposals = 700;
    c.stats.accepted = 321;
    c.stats.rays = 12345;
    c.stats.largeSteps = 70;
    c.stats.bootstrapSamples = 4096;
    c.stats.traceSeconds = 1.5;
    c.b.sum = 3.25;
    c.b.count = 4166;
    c.b.b0 = 0.00078;
    c.pixelWeight = {0.5f, 1.0f, 0.25f, 0.75f};
    c.fine = {1, 2, 3, 4, 5, 6};
    c.coarse = {7, 8};
    c.pos = {Vec2f(0.5f, 1.5f), Vec2f(2.5f, 3.5f)};
    c.value = {Spectrum(1, 2, 3), Spectrum(4, 5, 6)};
    c.importance = {0.125f, 2.0f};
    c.usedDims = {11, 18};
    c.image.assign(kMltValuesPerPixel * 4, 0.0);
    for (size_t i = 0; i < c.image.size(); ++i) c.image[i] = 0.1 * double(i);
    // Batches of 4 iterations, 2 splats an iteration: 7 iterations leave 3 x 2 splats pending.
    for (int i = 0; i < 6; ++i)
        c.pendingSplats.push_back(MltSplat{Vec2f(0.25f * float(i), 1), Spectrum(float(i)), Spectrum(0.5f * float(i))});
    return c;
}

MltCheckpointSizes sizesOf(const MltCheckpoint& c) {
    MltCheckpointSizes s;
    s.pixelWeights = c.pixelWeight.size();
    s.fine = c.fine.size();
    s.coarse = c.coarse.size();
    s.values = c.values.size();
    s.chains = c.pos.size();
    s.image = c.image.size();
    s.splatsPerIteration = 2;
    s.splatBatch = 4;
    return s;
}

const MltCheckpointKeys kKeys = {{"width", 2}, {"height", 2}, {"chains", 2}};

std::string written(const MltCheckpoint& c, const MltCheckpointKeys& keys = kKeys) {
    std::stringstream out;
    writeMltCheckpoint(out, keys, c);
    return out.str();
}

std::string readError(const std::string& bytes, const MltCheckpointKeys& keys,
                      const MltCheckpointSizes& sizes) {
    std::stringstream in(bytes);
    try {
        readMltCheckpoint(in, keys, sizes, MltStats());
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(MltCheckpointFile, ReadsBackWhatWasWritten) {
    const MltCheckpoint c = someCheckpoint();
    std::stringstream in(written(c));
    MltStats current;
    current.bytesPerChain = 99;  // not in the file: kept from the renderer
    const MltCheckpoint r = readMltCheckpoint(in, kKeys, sizesOf(c), current);
    EXPECT_EQ(r.stats.iterations, 7u);
    EXPECT_EQ(r.stats.proposals, 700u);
    EXPECT_EQ(r.stats.accepted, 321u);
    EXPECT_EQ(r.stats.rays, 12345u);
    EXPECT_EQ(r.stats.largeSteps, 70u);
    EXPECT_EQ(r.stats.bootstrapSamples, 4096u);
    EXPECT_EQ(r.stats.traceSeconds, 1.5);
    EXPECT_EQ(r.stats.bytesPerChain, 99u);
    EXPECT_EQ(r.b.sum, c.b.sum);
    EXPECT_EQ(r.b.count, c.b.count);
    EXPECT_EQ(r.b.b0, c.b.b0);
    EXPECT_EQ(r.stats.b, c.b.b());
    EXPECT_EQ(r.pixelWeight, c.pixelWeight);
    EXPECT_EQ(r.fine, c.fine);
    EXPECT_EQ(r.coarse, c.coarse);
    EXPECT_TRUE(r.values.empty());
    ASSERT_EQ(r.pos.size(), 2u);
    EXPECT_EQ(r.pos[1].x, 2.5f);
    EXPECT_EQ(r.value[1].g, 5.0f);
    EXPECT_EQ(r.importance, c.importance);
    EXPECT_EQ(r.usedDims, c.usedDims);
    EXPECT_EQ(r.image, c.image);
    ASSERT_EQ(r.pendingSplats.size(), 6u);
    EXPECT_EQ(r.pendingSplats[5].pos.x, 1.25f);
    EXPECT_EQ(r.pendingSplats[5].value.b, 5.0f);
    EXPECT_EQ(r.pendingSplats[5].largeValue.r, 2.5f);
}

TEST(MltCheckpointFile, RefusesOtherSettingsSizesAndDamageByName) {
    const MltCheckpoint c = someCheckpoint();
    const std::string bytes = written(c);
    MltCheckpointKeys other = kKeys;
    other[2].value = 3;
    const std::string chains = readError(bytes, other, sizesOf(c));
    EXPECT_NE(chains.find("chains differs (written for 2; now 3)"), std::string::npos) << chains;
    MltCheckpointSizes sizes = sizesOf(c);
    sizes.pixelWeights = 0;  // a luminance-target render
    EXPECT_NE(readError(bytes, kKeys, sizes).find("pixel weights holds 4 values, expected 0"),
              std::string::npos);
    sizes = sizesOf(c);
    sizes.splatBatch = 8;  // 7 iterations of an unfinished batch would be pending
    EXPECT_NE(readError(bytes, kKeys, sizes).find("unfinished splat batch holds 6 values, expected 14"),
              std::string::npos);
    std::string damaged = bytes;
    damaged[damaged.size() - 12] ^= 0x10;
    EXPECT_NE(readError(damaged, kKeys, sizesOf(c)).find("checksum"), std::string::npos);
    EXPECT_NE(readError(bytes.substr(0, bytes.size() - 3), kKeys, sizesOf(c)).find("truncated"),
              std::string::npos);
    EXPECT_NE(readError("CAMLTCK0 and more bytes", kKeys, sizesOf(c)).find("bad magic"),
              std::string::npos);
    EXPECT_EQ(readError(bytes, kKeys, sizesOf(c)), "");
}

// A mismatch prints the settings as a user gives them: floats in their shortest form (not their
// bits), signed depths, names for kinds and filters.
TEST(MltCheckpointFile, MismatchesPrintValuesNotBits) {
    const MltCheckpoint c = someCheckpoint();
    MltStepParams params;
    params.width = params.height = 2;
    MltSettings settings;
    settings.chains = 2;
    settings.largeStepProbability = 0.3f;
    const Filter gaussian = Filter::fromDesc(FilterDesc{});
    const std::string bytes = written(c, mltCheckpointKeys(params, settings, 8, gaussian));
    // The error reading `bytes` as a checkpoint of a render with these settings holds `text`.
    auto expectMismatch = [&](const MltStepParams& p, const MltSettings& s, const Filter& f,
                              const std::string& text) {
        const std::string error = readError(bytes, mltCheckpointKeys(p, s, 8, f), sizesOf(c));
        EXPECT_NE(error.find(text), std::string::npos) << error;
    };
    EXPECT_EQ(readError(bytes, mltCheckpointKeys(params, settings, 8, gaussian), sizesOf(c)), "");
    MltSettings other = settings;
    other.largeStepProbability = 0.1f;
    expectMismatch(params, other, gaussian,
                   "MLT checkpoint: large-step probability differs (written for 0.3; now 0.1)");
    other = settings;
    other.mutation.s1 = 0.002f;
    expectMismatch(params, other, gaussian, "s1 differs (written for 0.0009765625; now 0.002)");
    other = settings;
    other.state = MltStateKind::Float;
    expectMismatch(params, other, gaussian, "chain state differs (written for compact; now float)");
    MltStepParams bounded = params;
    bounded.path.maxDepth = 8;
    expectMismatch(bounded, settings, gaussian, "max depth differs (written for -1; now 8)");
    expectMismatch(params, settings, Filter::box(),
                   "filter differs (written for gaussian of radius 2; now box of radius 0.5)");
}

// A setting read from the header of a file that checks out, and nothing from one that does not.
TEST(MltCheckpointFile, PeeksAKeyOfAWholeFileOnly) {
    const std::string bytes = written(someCheckpoint(), {{"width", 2}, {"height", 2}, {"chains", 37}});
    auto peek = [&](const std::string& file, const char* name) {
        std::stringstream in(file);
        return peekMltCheckpointKey(in, kKeys, name);
    };
    EXPECT_EQ(peek(bytes, "chains"), std::optional<uint64_t>(37));
    EXPECT_EQ(peek(bytes, "height"), std::optional<uint64_t>(2));
    EXPECT_EQ(peek(bytes, "seed"), std::nullopt);  // not among the keys
    std::string damaged = bytes;
    damaged[damaged.size() - 12] ^= 0x10;
    EXPECT_EQ(peek(damaged, "chains"), std::nullopt);
    EXPECT_EQ(peek(bytes.substr(0, bytes.size() - 3), "chains"), std::nullopt);
    EXPECT_EQ(peek("CAMLTCK0 and more bytes", "chains"), std::nullopt);
    EXPECT_EQ(peek("", "chains"), std::nullopt);
    // Larger than the reader's chunk: the checksum still covers the whole file.
    MltCheckpoint big = someCheckpoint();
    big.image.assign(kMltValuesPerPixel * 40000, 0.5);
    std::string bigBytes = written(big, {{"width", 200}, {"height", 200}, {"chains", 2}});
    EXPECT_EQ(peek(bigBytes, "width"), std::optional<uint64_t>(200));
    bigBytes[bigBytes.size() / 2] ^= 0x01;
    EXPECT_EQ(peek(bigBytes, "width"), std::nullopt);
}

// The GPU keeps slot s of chain c at s * chains + c (cells of 3 bytes for the fine store); the
// file holds c * slots + s.
TEST(MltCheckpointFile, TransposeCellsMovesCellsAndRoundTrips) {
    const size_t slots = 2, chains = 3;
    std::vector<uint8_t> dimMajor;  // cell (s, c) = bytes {10s+c, 100+10s+c, 200+10s+c}
    for (size_t s = 0; s < slots; ++s)
        for (size_t c = 0; c < chains; ++c)
            for (int k = 0; k < 3; ++k) dimMajor.push_back(uint8_t(100 * k + 10 * s + c));
    const std::vector<uint8_t> chainMajor = mltTransposeCells(dimMajor, slots, chains, 3);
    for (size_t c = 0; c < chains; ++c)
        for (size_t s = 0; s < slots; ++s)
            for (size_t k = 0; k < 3; ++k)
                EXPECT_EQ(chainMajor[(c * slots + s) * 3 + k], uint8_t(100 * k + 10 * s + c))
                    << c << " " << s;
    EXPECT_EQ(mltTransposeCells(chainMajor, chains, slots, 3), dimMajor);
    // No slots: the one-element placeholder a driver allocates stays as it is.
    EXPECT_EQ(mltTransposeCells(std::vector<uint16_t>{42}, 0, chains, 1),
              std::vector<uint16_t>{42});
}

}  // namespace
}  // namespace caustica
