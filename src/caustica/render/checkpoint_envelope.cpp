#include "caustica/render/checkpoint_envelope.h"

#include <cstring>
#include <istream>
#include <ostream>

#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

constexpr char kMagic[8] = {'C', 'A', 'U', 'S', 'T', 'C', 'K', 'P'};
constexpr uint32_t kVersion = 1;
constexpr uint64_t kMaxString = uint64_t(1) << 20;  // a corrupt length must not allocate gigabytes
constexpr uint64_t kMaxEntries = uint64_t(1) << 16;

void writeString(BinaryWriter& w, const std::string& s) {
    w.u64(s.size());
    w.bytes(s.data(), s.size());
}

std::string readString(BinaryReader& r) {
    const uint64_t n = r.u64();
    if (n > kMaxString) throw Error("damaged checkpoint (a string of " + std::to_string(n) + " bytes)");
    std::string s(size_t(n), '\0');
    r.bytes(s.data(), s.size());
    return s;
}

}  // namespace

void writeCheckpointHeader(std::ostream& out, const CheckpointHeader& h) {
    BinaryWriter w(out, "checkpoint");
    w.bytes(kMagic, sizeof kMagic);
    w.u32(kVersion);
    writeString(w, h.integrator);
    w.u64(h.identity.size());
    for (const IdentityEntry& e : h.identity) {
        writeString(w, e.name);
        writeString(w, e.value);
        writeString(w, e.identity);
    }
    w.f64(h.seconds);
    w.f64(h.samplesPerPixel);
    w.u64(w.hash());
}

CheckpointHeader readCheckpointHeader(std::istream& in) {
    BinaryReader r(in, "checkpoint");
    char magic[sizeof kMagic] = {};
    try {
        r.bytes(magic, sizeof magic);
    } catch (const Error&) {
        throw Error("not a caustica checkpoint (too short)");
    }
    if (std::memcmp(magic, kMagic, sizeof magic) != 0)
        throw Error("not a caustica checkpoint of this version (written by an older caustica, or another file)");
    const uint32_t version = r.u32();
    if (version != kVersion)
        throw Error("checkpoint format version " + std::to_string(version) + ", this caustica reads version " +
                    std::to_string(kVersion));
    CheckpointHeader h;
    h.integrator = readString(r);
    const uint64_t n = r.u64();
    if (n > kMaxEntries) throw Error("damaged checkpoint (" + std::to_string(n) + " settings)");
    for (uint64_t i = 0; i < n; ++i) {
        IdentityEntry e;
        e.name = readString(r);
        e.value = readString(r);
        e.identity = readString(r);
        h.identity.push_back(std::move(e));
    }
    h.seconds = r.f64();
    h.samplesPerPixel = r.f64();
    const uint64_t expected = r.hash();
    if (r.u64() != expected) throw Error("damaged checkpoint (its header's checksum does not match)");
    return h;
}

std::string checkpointMismatch(const CheckpointHeader& saved, const std::string& integrator,
                               const RenderIdentity& identity) {
    if (saved.integrator != integrator)
        return "integrator differs (written for " + saved.integrator + "; now " + integrator + ")";
    return firstIdentityDifference(saved.identity, identity);
}

}  // namespace caustica
