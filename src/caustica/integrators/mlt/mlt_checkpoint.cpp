#include "caustica/integrators/mlt/mlt_checkpoint.h"

#include <algorithm>
#include <cstring>
#include <istream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

constexpr char kMagic[8] = {'C', 'A', 'M', 'L', 'T', 'C', 'K', '1'};
constexpr uint32_t kVersion = 2;  // 2: b0 and the large-step layer of the splat sums

uint64_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return uint64_t(u);
}

}  // namespace

MltCheckpointKeys mltCheckpointKeys(const MltStepParams& params, const MltSettings& settings, uint32_t storedDims,
                                    const Filter& filter) {
    return {{"width", uint64_t(params.width)},
            {"height", uint64_t(params.height)},
            {"seed", params.seed},
            {"chains", settings.chains},
            {"proposals", settings.proposals},
            {"state (0 compact, 1 float)", uint64_t(settings.state)},
            {"target (0 luminance, 1 relative)", uint64_t(settings.target)},
            {"stored dimensions", storedDims},
            {"large-step probability bits", floatBits(settings.largeStepProbability)},
            {"s1 bits", floatBits(settings.mutation.s1)},
            {"s2 bits", floatBits(settings.mutation.s2)},
            {"max depth", uint64_t(int64_t(params.path.maxDepth))},
            {"rr depth", uint64_t(int64_t(params.path.rrDepth))},
            {"filter (type x 2^32 + radius bits)", (uint64_t(filter.type) << 32) | floatBits(filter.radius)}};
}

std::optional<uint64_t> peekMltCheckpointKey(std::istream& in, const MltCheckpointKeys& keys, std::string_view name) {
    // The checksum first, streaming: the last 8 bytes are the FNV-1a hash of all before them.
    Fnv1a hash;
    std::vector<char> chunk(size_t(1) << 20);
    std::string head, tail;  // the file's first bytes (the header), its last 8 (the hash)
    const size_t headBytes = sizeof kMagic + 4 + 8 * keys.size();
    while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0) {
        tail.append(chunk.data(), size_t(in.gcount()));
        if (head.size() < headBytes) head.append(tail, 0, std::min(headBytes - head.size(), tail.size()));
        if (tail.size() > 8) {
            hash.add(reinterpret_cast<const unsigned char*>(tail.data()), tail.size() - 8);
            tail.erase(0, tail.size() - 8);
        }
    }
    if (head.size() < headBytes || tail.size() < 8) return std::nullopt;
    uint64_t saved = 0;
    for (int i = 0; i < 8; ++i) saved |= uint64_t(static_cast<unsigned char>(tail[size_t(i)])) << (8 * i);
    if (saved != hash.h) return std::nullopt;
    std::istringstream header(head);
    BinaryReader r(header, "MLT checkpoint");
    char magic[sizeof kMagic];
    r.bytes(magic, sizeof magic);
    if (std::memcmp(magic, kMagic, sizeof magic) != 0 || r.u32() != kVersion) return std::nullopt;
    std::optional<uint64_t> found;
    for (const auto& key : keys) {
        const uint64_t value = r.u64();
        if (name == key.first) found = value;
    }
    return found;
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
    return c;
}

void writeMltCheckpoint(std::ostream& out, const MltCheckpointKeys& keys, const MltCheckpoint& c) {
    BinaryWriter w(out, "MLT checkpoint");
    w.bytes(kMagic, sizeof kMagic);
    w.u32(kVersion);
    for (const auto& [name, value] : keys) w.u64(value);
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
    for (const auto& [name, value] : keys)
        if (const uint64_t saved = r.u64(); saved != value)
            throw Error(std::string("MLT checkpoint: rendered with ") + name + " " + std::to_string(saved) +
                        ", this render has " + std::to_string(value) + "; resume with the same settings");
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
    r.checkHash();
    return c;
}

void restoreMltCheckpoint(const MltCheckpoint& c, MltStats& stats, MltNormalisation& b, MltChainBuffers& buffers) {
    buffers.pos.copyFromHost(c.pos);
    buffers.value.copyFromHost(c.value);
    buffers.importance.copyFromHost(c.importance);
    buffers.usedDims.copyFromHost(c.usedDims);
    buffers.image.copyFromHost(c.image);
    b = c.b;
    stats = c.stats;
}

}  // namespace caustica
