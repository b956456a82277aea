// ply_writer.h — writes small PLY files in any of the three encodings for the loader tests.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace caustica::test {

/// Writes PLY files in any of the three encodings.
class PlyWriter {
public:
    enum Format { Ascii, Little, Big };
    explicit PlyWriter(Format f) : format_(f) {}
    std::string header;
    void line() {
        if (format_ == Ascii) body_ += "\n";
    }
    template <class T>
    void put(T v) {
        if (format_ == Ascii) {
            if constexpr (sizeof(T) == 1)
                body_ += std::to_string(int(v)) + " ";
            else
                body_ += std::to_string(v) + " ";
            return;
        }
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        bool swap = (format_ == Big) != (std::endian::native == std::endian::big);
        if (swap) std::reverse(b, b + sizeof(T));
        body_.append(reinterpret_cast<const char*>(b), sizeof(T));
    }
    std::string file() const {
        const char* f[] = {"ascii", "binary_little_endian", "binary_big_endian"};
        return "ply\nformat " + std::string(f[format_]) + " 1.0\ncomment test\n" + header +
               "end_header\n" + body_;
    }

private:
    Format format_;
    std::string body_;
};

/// A unit square (quad, uint indices, uchar count) plus a triangle (int count), with normals,
/// s/t texture coordinates, an extra colour property, a skipped list and a skipped element.
inline std::string squarePly(PlyWriter::Format format) {
    PlyWriter w(format);
    w.header =
        "element vertex 5\nproperty float x\nproperty float y\nproperty double z\n"
        "property uchar red\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "property list uchar int tags\nproperty float s\nproperty float t\n"
        "element material 1\nproperty list ushort double weights\nproperty short id\n"
        "element face 2\nproperty list uchar uint vertex_indices\nproperty int flags\n";
    const float p[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 2, 1}};
    for (int i = 0; i < 5; ++i) {
        w.put(p[i][0]), w.put(p[i][1]), w.put(double(p[i][2]));
        w.put(uint8_t(200));
        w.put(0.0f), w.put(0.0f), w.put(1.0f);
        w.put(uint8_t(i % 2));  // list of i % 2 ints
        for (int k = 0; k < i % 2; ++k) w.put(int32_t(-k));
        w.put(p[i][0] * 0.5f), w.put(p[i][1] * 0.25f);
        w.line();
    }
    w.put(uint16_t(2)), w.put(0.5), w.put(0.25), w.put(int16_t(-3));
    w.line();
    w.put(uint8_t(4));
    for (uint32_t i : {0u, 1u, 2u, 3u}) w.put(i);
    w.put(int32_t(7));
    w.line();
    w.put(uint8_t(3));
    for (uint32_t i : {1u, 4u, 2u}) w.put(i);
    w.put(int32_t(0));
    w.line();
    return w.file();
}

}  // namespace caustica::test
