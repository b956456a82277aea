// serialized_loader.cpp — Mitsuba's `.serialized` mesh format (see serialized_loader.h and the
// format description in Mitsuba 3's src/shapes/serialized.cpp). Nothing is sized from the counts
// the file claims: arrays grow as the decompressed data arrives, so a lying header costs at most
// the data that is really there.
#include "caustica/io/mesh/serialized_loader.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>

#include "caustica/io/mesh/read_file.h"
#include "caustica/util/error.h"

namespace caustica::meshio {

namespace {

constexpr uint16_t kHeader = 0x041C;
constexpr uint16_t kVersion3 = 3, kVersion4 = 4;
enum Flags : uint32_t {
    kHasNormals = 0x0001,
    kHasTexcoords = 0x0002,
    kHasColors = 0x0008,
    kFaceNormals = 0x0010,
    kDoublePrecision = 0x2000,
};
constexpr size_t kMaxName = 1 << 16;

/// Little-endian unsigned integer of `n` bytes at `p`.
uint64_t readLE(const unsigned char* p, size_t n) {
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v |= uint64_t(p[i]) << (8 * i);
    return v;
}

/// Pull-style reader over one zlib stream (Mitsuba's ZStream: zlib header, window 15). Fails with
/// the loader's error when the stream is corrupt or ends before the bytes asked for.
class ZReader {
public:
    ZReader(const std::string& path, const unsigned char* data, size_t size) : path_(path) {
        zs_.next_in = const_cast<Bytef*>(data);
        zs_.avail_in = 0;
        remaining_ = size;
        if (inflateInit2(&zs_, 15) != Z_OK) fail("cannot initialise zlib");
    }
    ~ZReader() { inflateEnd(&zs_); }
    ZReader(const ZReader&) = delete;
    ZReader& operator=(const ZReader&) = delete;

    /// Reads exactly n bytes into out; `what` names the data in the error when the stream ends.
    void read(void* out, size_t n, const std::string& what) {
        zs_.next_out = static_cast<Bytef*>(out);
        while (n > 0) {
            if (ended_) fail("compressed data ends inside " + what);
            const uInt chunkOut = uInt(std::min<size_t>(n, 1u << 30));
            zs_.avail_out = chunkOut;
            if (zs_.avail_in == 0) {
                const uInt chunkIn = uInt(std::min<size_t>(remaining_, 1u << 30));
                zs_.avail_in = chunkIn;
                remaining_ -= chunkIn;
            }
            const int rc = inflate(&zs_, Z_NO_FLUSH);
            const size_t produced = chunkOut - zs_.avail_out;
            n -= produced;
            if (rc == Z_STREAM_END) {
                ended_ = true;
            } else if (rc == Z_BUF_ERROR && zs_.avail_in == 0 && remaining_ == 0) {
                fail("file ends inside the compressed data of " + what);
            } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
                fail(std::string("corrupt compressed data (zlib: ") +
                     (zs_.msg ? zs_.msg : "error " + std::to_string(rc)) + ")");
            }
        }
    }
    template <class T>
    T value(const std::string& what) {
        unsigned char b[sizeof(T)];
        read(b, sizeof(T), what);
        return T(readLE(b, sizeof(T)));
    }

    [[noreturn]] void fail(const std::string& reason) const { throw Error(path_, 0, reason); }

private:
    const std::string& path_;
    z_stream zs_{};
    size_t remaining_ = 0;
    bool ended_ = false;
};

/// Reads count * dim floats (or doubles) as floats, in chunks, calling put(i, value).
template <class Put>
void readReals(ZReader& z, uint64_t count, int dim, bool dp, const std::string& what, Put put) {
    const size_t width = dp ? 8 : 4;
    std::vector<unsigned char> buf;
    const uint64_t total = count * uint64_t(dim);
    for (uint64_t done = 0; done < total;) {
        const size_t n = size_t(std::min<uint64_t>(total - done, 1 << 16));
        buf.resize(n * width);
        z.read(buf.data(), buf.size(), what);
        for (size_t i = 0; i < n; ++i) {
            const uint64_t bits = readLE(buf.data() + i * width, width);
            float v;
            if (dp) {
                double d;
                std::memcpy(&d, &bits, 8);
                v = float(d);
            } else {
                const uint32_t b32 = uint32_t(bits);
                std::memcpy(&v, &b32, 4);
            }
            put(done + i, v);
        }
        done += n;
    }
}

}  // namespace

SerializedMesh loadSerialized(const std::string& path, int shapeIndex) {
    const std::string bytes = readWholeFile(path, "mesh file");
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const size_t size = bytes.size();
    auto fail = [&](const std::string& reason) -> void { throw Error(path, 0, reason); };

    if (shapeIndex < 0) fail("shape_index must not be negative");
    if (size < 4) fail("file is too short for a .serialized header");
    if (readLE(data, 2) != kHeader) fail("not a .serialized file (the header is not 0x041C)");
    const uint16_t version = uint16_t(readLE(data + 2, 2));
    if (version != kVersion3 && version != kVersion4)
        fail("unsupported .serialized version " + std::to_string(version) + " (3 and 4 are read)");

    // Mesh k > 0: its offset is in the end-of-file dictionary.
    size_t offset = 0;
    if (shapeIndex > 0) {
        if (size < 8) fail("file is too short for the end-of-file mesh dictionary");
        const uint64_t count = readLE(data + size - 4, 4);
        if (uint64_t(shapeIndex) >= count)
            fail("shape_index " + std::to_string(shapeIndex) + " is out of range (the file has " +
                 std::to_string(count) + " mesh" + (count == 1 ? "" : "es") + ")");
        const size_t width = version == kVersion4 ? 8 : 4;
        if (count > (size - 4) / width)
            fail("mesh dictionary of " + std::to_string(count) + " entries exceeds the file size");
        const size_t entry = size - 4 - width * size_t(count - uint64_t(shapeIndex));
        const uint64_t at = readLE(data + entry, width);
        if (at > size - 4)  // not at + 4 > size: `at` may be near 2^64
            fail("mesh " + std::to_string(shapeIndex) + " starts at byte " + std::to_string(at) +
                 ", beyond the end of the file");
        offset = size_t(at);
        if (readLE(data + offset, 2) != kHeader || readLE(data + offset + 2, 2) != version)
            fail("mesh " + std::to_string(shapeIndex) + " at byte " + std::to_string(offset) +
                 " does not start with a .serialized header");
    }

    ZReader z(path, data + offset + 4, size - offset - 4);
    SerializedMesh out;
    const uint32_t flags = z.value<uint32_t>("the mesh flags");
    if (version == kVersion4) {
        for (;;) {
            const char ch = char(z.value<uint8_t>("the mesh name"));
            if (ch == 0) break;
            if (out.name.size() >= kMaxName) fail("mesh name is longer than 65536 bytes");
            out.name += ch;
        }
    }
    const uint64_t vertexCount = z.value<uint64_t>("the vertex count");
    const uint64_t triangleCount = z.value<uint64_t>("the triangle count");
    if (vertexCount == 0) fail("mesh has no vertices");
    if (triangleCount == 0) fail("mesh has no triangles");
    if (vertexCount >= 0xffffffffull || triangleCount >= 0xffffffffull / 3)
        fail("mesh has too many vertices or triangles (" + std::to_string(vertexCount) + ", " +
             std::to_string(triangleCount) + "; the limit is 2^32 - 1 indices)");

    const bool dp = (flags & kDoublePrecision) != 0;
    out.faceNormals = (flags & kFaceNormals) != 0;
    TriangleMesh& m = out.mesh;
    auto grow = [](auto& v, uint64_t i) {
        if (i >= v.size()) v.resize(size_t(std::max<uint64_t>(i + 1, v.size() * 2)));
    };
    readReals(z, vertexCount, 3, dp, "the vertex positions", [&](uint64_t i, float v) {
        grow(m.positions, i / 3);
        m.positions[size_t(i / 3)][int(i % 3)] = v;
    });
    m.positions.resize(size_t(vertexCount));
    if (flags & kHasNormals) {
        readReals(z, vertexCount, 3, dp, "the vertex normals", [&](uint64_t i, float v) {
            grow(m.normals, i / 3);
            m.normals[size_t(i / 3)][int(i % 3)] = v;
        });
        m.normals.resize(size_t(vertexCount));
    }
    if (flags & kHasTexcoords) {
        readReals(z, vertexCount, 2, dp, "the texture coordinates", [&](uint64_t i, float v) {
            grow(m.uvs, i / 2);
            (i % 2 ? m.uvs[size_t(i / 2)].y : m.uvs[size_t(i / 2)].x) = v;
        });
        m.uvs.resize(size_t(vertexCount));
    }
    if (flags & kHasColors)  // vertex colours: skipped, as Mitsuba 3 does
        readReals(z, vertexCount, 3, dp, "the vertex colours", [](uint64_t, float) {});

    std::vector<unsigned char> buf;
    const uint64_t indexCount = triangleCount * 3;
    for (uint64_t done = 0; done < indexCount;) {
        const size_t n = size_t(std::min<uint64_t>(indexCount - done, 1 << 16));
        buf.resize(n * 4);
        z.read(buf.data(), buf.size(), "the triangle indices");
        for (size_t i = 0; i < n; ++i) {
            const uint64_t k = done + i;
            const uint32_t index = uint32_t(readLE(buf.data() + 4 * i, 4));
            if (index >= vertexCount)
                fail("triangle " + std::to_string(k / 3) + " references vertex " +
                     std::to_string(index) + " but the mesh has " + std::to_string(vertexCount) +
                     " vertices");
            grow(m.triangles, k / 3);
            Vec3u& tri = m.triangles[size_t(k / 3)];
            (k % 3 == 0 ? tri.x : k % 3 == 1 ? tri.y : tri.z) = index;
        }
        done += n;
    }
    m.triangles.resize(size_t(triangleCount));
    validateMesh(m, path);
    return out;
}

}  // namespace caustica::meshio
