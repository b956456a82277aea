#include "caustica/io/hdr_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "caustica/util/error.h"

namespace caustica {

namespace {

constexpr size_t kMaxHeaderLine = 4096;

/// RGBE -> float as Walter's rgbe.c (Mitsuba's reader): m · 2^(e − 136), black for e = 0.
void rgbeToFloat(const unsigned char* rgbe, float* rgb) {
    if (rgbe[3] == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    const float f = std::ldexp(1.0f, int(rgbe[3]) - (128 + 8));
    for (int c = 0; c < 3; ++c) rgb[c] = float(rgbe[c]) * f;
}

}  // namespace

Image decodeRadianceHdr(const std::string& path, const std::vector<unsigned char>& data) {
    size_t pos = 0;
    auto fail = [&](const std::string& reason) -> void { throw Error(path, 0, reason); };
    auto readLine = [&]() {
        std::string line;
        while (true) {
            if (pos >= data.size()) fail("corrupt header: ends before the resolution line");
            const char c = char(data[pos++]);
            if (c == '\n') return line;
            line += c;
            if (line.size() > kMaxHeaderLine) fail("corrupt header: line too long");
        }
    };
    const std::string magic = readLine();
    if (magic.rfind("#?RADIANCE", 0) != 0 && magic.rfind("#?RGBE", 0) != 0)
        fail("corrupt header: not a Radiance HDR file");
    for (std::string line = readLine(); !line.empty(); line = readLine())
        if (line.rfind("FORMAT=", 0) == 0 && line != "FORMAT=32-bit_rle_rgbe")
            fail("unsupported pixel format '" + line.substr(7) + "' (expected 32-bit_rle_rgbe)");
    const std::string res = readLine();
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(res.c_str(), "-Y %d +X %d%c", &h, &w, &tail) != 2)
        fail("corrupt header: unsupported resolution line '" + res.substr(0, 64) +
             "' (expected '-Y height +X width')");
    if (w <= 0 || h <= 0 || uint64_t(w) * uint64_t(h) > kMaxImagePixels)
        fail("corrupt header: absurd image size " + std::to_string(w) + " x " + std::to_string(h));
    // A scanline takes at least 4 · w bytes (flat) or 4 + 2 bytes per run of at most 127 values
    // per channel (RLE): a header claiming more than the file can hold is refused before
    // anything is allocated.
    const uint64_t minLine = std::min<uint64_t>(4 + 8 * ((uint64_t(w) + 126) / 127), 4 * uint64_t(w));
    if (uint64_t(data.size() - pos) < minLine * uint64_t(h))
        fail("truncated data: " + std::to_string(data.size() - pos) + " bytes cannot hold " +
             std::to_string(w) + " x " + std::to_string(h) + " pixels");
    Image image(w, h);
    std::vector<unsigned char> scan(size_t(w) * 4);
    auto need = [&](size_t n) {
        if (data.size() - pos < n) fail("truncated data: file ends inside scanline data");
    };
    for (int y = 0; y < h; ++y) {
        const bool rle = w >= 8 && w < 32768 && data.size() - pos >= 4 && data[pos] == 2 &&
                         data[pos + 1] == 2 && (data[pos + 2] & 0x80) == 0;
        if (!rle) {  // flat scanline
            need(size_t(w) * 4);
            std::copy(data.begin() + std::ptrdiff_t(pos), data.begin() + std::ptrdiff_t(pos) + w * 4,
                      scan.begin());
            pos += size_t(w) * 4;
        } else {
            if (((int(data[pos + 2]) << 8) | int(data[pos + 3])) != w)
                fail("corrupt data: scanline " + std::to_string(y) + " has the wrong width");
            pos += 4;
            for (int c = 0; c < 4; ++c) {
                for (int x = 0; x < w;) {
                    need(1);
                    int count = data[pos++];
                    const bool run = count > 128;
                    if (run) count -= 128;
                    if (count == 0 || x + count > w)
                        fail("corrupt data: bad run length in scanline " + std::to_string(y));
                    need(run ? 1 : size_t(count));
                    for (int i = 0; i < count; ++i)
                        scan[size_t(x + i) * 4 + size_t(c)] = run ? data[pos] : data[pos + size_t(i)];
                    pos += run ? 1 : size_t(count);
                    x += count;
                }
            }
        }
        for (int x = 0; x < w; ++x) rgbeToFloat(&scan[size_t(x) * 4], image.pixel(x, y));
    }
    return image;
}

}  // namespace caustica
