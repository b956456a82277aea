// binary_io.h — the checkpoint files' little-endian writer and reader with a running FNV-1a hash,
// so a file can end in the hash of everything before it and a reader can tell a damaged file
// from a good one. Errors name `what` (e.g. "film checkpoint").
//
//     BinaryWriter w(out, "film checkpoint");  w.u32(version);  w.array(values, n);  w.u64(w.hash());
//     BinaryReader r(in, "film checkpoint");   r.u32();  r.array(values, n);  r.u64() == hash?
#pragma once

#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
#include <string>

#include "caustica/util/error.h"

namespace caustica {

struct Fnv1a {
    uint64_t h = 0xcbf29ce484222325ull;
    void add(const unsigned char* p, size_t n) {
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    }
};

class BinaryWriter {
public:
    BinaryWriter(std::ostream& out, std::string what) : out_(out), what_(std::move(what)) {}
    void bytes(const void* p, size_t n) {
        hash_.add(static_cast<const unsigned char*>(p), n);
        out_.write(static_cast<const char*>(p), std::streamsize(n));
        if (!out_) throw Error(what_ + ": write failed");
    }
    /// An unsigned integer, little-endian.
    template <class T>
    void uint(T v) {
        unsigned char b[sizeof(T)];
        for (size_t i = 0; i < sizeof(T); ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
        bytes(b, sizeof(T));
    }
    void u64(uint64_t v) { uint(v); }
    void u32(uint32_t v) { uint(v); }
    void f32(float v) {
        uint32_t u;
        std::memcpy(&u, &v, 4);
        u32(u);
    }
    void f64(double v) {
        uint64_t u;
        std::memcpy(&u, &v, 8);
        u64(u);
    }
    /// n trivially copyable values in memory order (the machine's byte order: x86-64 and CUDA
    /// hosts are little-endian).
    template <class T>
    void array(const T* p, size_t n) {
        u64(n);
        bytes(p, n * sizeof(T));
    }
    uint64_t hash() const { return hash_.h; }

private:
    std::ostream& out_;
    std::string what_;
    Fnv1a hash_;
};

class BinaryReader {
public:
    BinaryReader(std::istream& in, std::string what) : in_(in), what_(std::move(what)) {}
    void bytes(void* p, size_t n) {
        if (!in_.read(static_cast<char*>(p), std::streamsize(n))) throw Error(what_ + ": truncated data");
        hash_.add(static_cast<const unsigned char*>(p), n);
    }
    /// An unsigned integer, little-endian.
    template <class T>
    T uint() {
        unsigned char b[sizeof(T)];
        bytes(b, sizeof(T));
        T v = 0;
        for (size_t i = 0; i < sizeof(T); ++i) v |= T(b[i]) << (8 * i);
        return v;
    }
    uint64_t u64() { return uint<uint64_t>(); }
    uint32_t u32() { return uint<uint32_t>(); }
    float f32() {
        uint32_t u = u32();
        float v;
        std::memcpy(&v, &u, 4);
        return v;
    }
    double f64() {
        uint64_t u = u64();
        double v;
        std::memcpy(&v, &u, 8);
        return v;
    }
    /// Reads what BinaryWriter::array wrote into exactly n values; a different count is an error
    /// naming `name`.
    template <class T>
    void array(T* p, size_t n, const char* name) {
        const uint64_t count = u64();
        if (count != n)
            throw Error(what_ + ": " + name + " holds " + std::to_string(count) + " values, expected " +
                        std::to_string(n));
        bytes(p, n * sizeof(T));
    }
    /// Reads the trailing hash and checks it against everything read before it.
    void checkHash() {
        const uint64_t expected = hash_.h;
        if (u64() != expected) throw Error(what_ + ": damaged (checksum mismatch)");
    }
    uint64_t hash() const { return hash_.h; }

private:
    std::istream& in_;
    std::string what_;
    Fnv1a hash_;
};

}  // namespace caustica
