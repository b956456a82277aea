#include "caustica/integrators/mlt/mlt_checkpoint.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

constexpr char kMagic[8] = {'C', 'A', 'M', 'L', 'T', 'C', 'K', '1'};
constexpr uint32_t kVersion = 3;  // 2: b0 and the large-step layer of the splat sums; 3: splat batches

uint64_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return uint64_t(u);
}

float bitsFloat(uint64_t bits) {
    const uint32_t u = uint32_t(bits);
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

/// The shortest decimal that reads back as the same float (0.1, not 0.100000001).
std::string showFloat(uint64_t bits) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, bitsFloat(bits));
    return std::string(buf, r.ptr);
}

std::string showSigned(uint64_t v) { return std::to_string(int64_t(v)); }  // -1: unbounded depth

std::string showState(uint64_t v) { return v == uint64_t(MltStateKind::Float) ? "float" : "compact"; }

std::string showTarget(uint64_t v) { return v == uint64_t(MltTarget::Relative) ? "relative" : "luminance"; }

/// A filter's key: its type in the high 32 bits, its radius's float bits in the low ones.
uint64_t filterKey(const Filter& filter) { return uint64_t(filter.type) << 32 | floatBits(filter.radius); }

std::string showFilter(uint64_t key) {
    static const char* const kNames[] = {"box", "tent", "gaussian"};
    const uint64_t type = key >> 32;
    return std::string(type < 3 ? kNames[type] : "unknown") + " of radius " + showFloat(key & 0xffffffffu);
}

}  // namespace

MltCheckpointKeys mltCheckpointKeys(const MltStepParams& params, const MltSettings& settings, uint32_t storedDims,
                                    const Filter& filter) {
    return {{"width", uint64_t(params.width)},
            {"height", uint64_t(params.height)},
            {"seed", params.seed},
            {"chains", settings.chains},
            {"proposals", settings.proposals},
            {"chain state", uint64_t(settings.state), showState},
            {"target", uint64_t(settings.target), showTarget},
            {"stored dimensions", storedDims},
            {"large-step probability", floatBits(settings.largeStepProbability), showFloat},
            {"small-step size s1", floatBits(settings.mutation.s1), showFloat},
            {"small-step size s2", floatBits(settings.mutation.s2), showFloat},
            {"max depth", uint64_t(int64_t(params.path.maxDepth)), showSigned},
            {"rr depth", uint64_t(int64_t(params.path.rrDepth)), showSigned},
            {"filter", filterKey(filter), showFilter},
            {"splat batch", mltSplatBatch(settings, uint32_t(params.width) * uint32_t(params.height))}};
}

std::optional<uint64_t> peekMltCheckpointKey(std::istream& in, const MltCheckpointKeys& keys, std::string_view name) {
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0);
    const uint64_t headerBytes = sizeof kMagic + 4 + 8 * uint64_t(keys.size());
    if (!in || size < 0 || uint64_t(size) < headerBytes + 8) return std::nullopt;
    try {
        BinaryReader r(in, "MLT checkpoint");
        char magic[sizeof kMagic];
        r.bytes(magic, sizeof magic);
        if (std::memcmp(magic, kMagic, sizeof magic) != 0 || r.u32() != kVersion) return std::nullopt;
        std::optional<uint64_t> found;
        for (const auto& key : keys)
            if (const uint64_t value = r.u64(); name == key.name) found = value;
        // The rest up to the trailing hash, in chunks, so that the whole file is checked.
        std::vector<char> chunk(size_t(1) << 20);
        for (uint64_t rest = uint64_t(size) - headerBytes - 8; rest > 0;) {
            const size_t n = size_t(std::min<uint64_t>(rest, chunk.size()));
            r.bytes(chunk.data(), n);
            rest -= n;
        }
        r.checkHash();
        return found;
    } catch (const Error&) {
        return std::nullopt;  // truncated or damaged
    }
}

MltCheckpoint mltCheckpointOf(const MltStats& stats, const MltNormalisation& b, const MltChainBuffers& buffers) {
    MltCheckpoint c;
    c.stats = stats;
    c.b = b;
    c.pos = buffers.pos.toHost();
    c.value = buffers.value.toHost();
    c.importance = buffers.importance.toHost();
    c.usedDims = buffers.usedDims.toHost();
    c.image = buffers.image.toHost();
    c.pendingSplats.resize(size_t(buffers.pendingIterations(stats.iterations)) * buffers.splatsPerIteration);
    buffers.splats.copyToHost(Span<MltSplat>(c.pendingSplats.data(), c.pendingSplats.size()));
    return c;
}

void writeMltCheckpoint(std::ostream& out, const MltCheckpointKeys& keys, const MltCheckpoint& c) {
    BinaryWriter w(out, "MLT checkpoint");
    w.bytes(kMagic, sizeof kMagic);
    w.u32(kVersion);
    for (const auto& key : keys) w.u64(key.value);
    const MltStats& s = c.stats;
    for (uint64_t v : {s.iterations, s.proposals, s.accepted, s.rays, s.largeSteps, s.bootstrapSamples}) w.u64(v);
    for (double t : {s.bootstrapSeconds, s.traceSeconds, s.advanceSeconds, s.splatSeconds, s.sortSeconds}) w.f64(t);
    w.f64(c.b.sum);
    w.f64(c.b.count);
    w.f64(c.b.b0);
    auto array = [&](const auto& v) { w.array(v.data(), v.size()); };
    array(c.pixelWeight);
    array(c.fine);
    array(c.coarse);
    array(c.values);
    array(c.pos);
    array(c.value);
    array(c.importance);
    array(c.usedDims);
    array(c.image);
    array(c.pendingSplats);
    w.u64(w.hash());
}

MltCheckpointSizes mltCheckpointSizes(const MltSettings& settings, uint32_t pixels, const MltChainBuffers& buffers,
                                      size_t fine, size_t coarse, size_t values) {
    MltCheckpointSizes sizes;
    sizes.pixelWeights = settings.target == MltTarget::Relative ? pixels : 0;
    sizes.fine = fine;
    sizes.coarse = coarse;
    sizes.values = values;
    sizes.chains = settings.chains;
    sizes.image = buffers.image.size();
    sizes.splatsPerIteration = buffers.splatsPerIteration;
    sizes.splatBatch = buffers.batch;
    return sizes;
}

MltCheckpoint readMltCheckpoint(std::istream& in, const MltCheckpointKeys& keys, const MltCheckpointSizes& sizes,
                                const MltStats& current) {
    BinaryReader r(in, "MLT checkpoint");
    char magic[sizeof kMagic];
    r.bytes(magic, sizeof magic);
    if (std::memcmp(magic, kMagic, sizeof magic) != 0)
        throw Error("MLT checkpoint: not an MLT checkpoint (bad magic number)");
    if (const uint32_t version = r.u32(); version != kVersion)
        throw Error("MLT checkpoint: unsupported version " + std::to_string(version));
    for (const auto& key : keys)
        if (const uint64_t saved = r.u64(); saved != key.value) {
            auto show = [&](uint64_t v) { return key.show ? key.show(v) : std::to_string(v); };
            throw Error(std::string("MLT checkpoint: ") + key.name + " differs (written for " + show(saved) +
                        "; now " + show(key.value) + "); resume with the same settings");
        }
    MltCheckpoint c;
    MltStats& s = c.stats;
    s = current;
    for (uint64_t* v : {&s.iterations, &s.proposals, &s.accepted, &s.rays, &s.largeSteps, &s.bootstrapSamples})
        *v = r.u64();
    for (double* t : {&s.bootstrapSeconds, &s.traceSeconds, &s.advanceSeconds, &s.splatSeconds, &s.sortSeconds})
        *t = r.f64();
    c.b.sum = r.f64();
    c.b.count = r.f64();
    c.b.b0 = r.f64();
    s.b = c.b.b();
    auto array = [&](auto& v, size_t n, const char* name) {
        v.resize(n);
        r.array(v.data(), n, name);
    };
    array(c.pixelWeight, sizes.pixelWeights, "pixel weights");
    array(c.fine, sizes.fine, "fine state");
    array(c.coarse, sizes.coarse, "coarse state");
    array(c.values, sizes.values, "float state");
    array(c.pos, sizes.chains, "positions");
    array(c.value, sizes.chains, "values");
    array(c.importance, sizes.chains, "importances");
    array(c.usedDims, sizes.chains, "used dimensions");
    array(c.image, sizes.image, "splat sums");
    array(c.pendingSplats, size_t(s.iterations % std::max<uint32_t>(sizes.splatBatch, 1)) * sizes.splatsPerIteration,
          "unfinished splat batch");
    r.checkHash();
    return c;
}

void restoreMltCheckpoint(const MltCheckpoint& c, MltStats& stats, MltNormalisation& b, MltChainBuffers& buffers) {
    buffers.pos.copyFromHost(c.pos);
    buffers.value.copyFromHost(c.value);
    buffers.importance.copyFromHost(c.importance);
    buffers.usedDims.copyFromHost(c.usedDims);
    buffers.image.copyFromHost(c.image);
    buffers.splats.copyFromHost(c.pendingSplats);
    b = c.b;
    stats = c.stats;
}

}  // namespace caustica
