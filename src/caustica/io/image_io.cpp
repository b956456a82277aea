// image_io.cpp — OpenEXR (via OpenEXR 3), PFM (by hand) and PNG (via stb) reading and writing;
// JPEG and Radiance HDR reading (via stb).
#include "caustica/io/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "caustica/io/hdr_reader.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

using Bytes = std::vector<unsigned char>;

enum class Format { Exr, Pfm, Png, Jpeg, Hdr };

/// The file name's extension after its last dot, in lower case ("" without one).
std::string lowerExtension(const std::string& path) {
    const std::string name = std::filesystem::path(path).filename().string();
    const size_t dot = name.rfind('.');
    std::string ext = dot == std::string::npos ? "" : name.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

Format formatOf(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "exr") return Format::Exr;
    if (ext == "pfm") return Format::Pfm;
    if (ext == "png") return Format::Png;
    if (ext == "jpg" || ext == "jpeg") return Format::Jpeg;
    if (ext == "hdr") return Format::Hdr;
    throw Error(path, 0,
                "unknown image file extension '" + ext + "' (expected .exr, .pfm, .png, .jpg, .hdr)");
}

void checkSize(const std::string& path, int64_t w, int64_t h) {
    if (w <= 0 || h <= 0 || uint64_t(w) * uint64_t(h) > kMaxImagePixels)
        throw Error(
            path, 0,
            "corrupt header: absurd image size " + std::to_string(w) + " x " + std::to_string(h));
}

Bytes readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, 0, "cannot open file for reading (missing or unreadable)");
    Bytes data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error(path, 0, "read error");
    return data;
}

void requireReadable(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, 0, "cannot open file for reading (missing or unreadable)");
}

std::string stbReason() {
    const char* r = stbi_failure_reason();
    return r && *r ? r : "decoding failed";
}

uint32_t readBe32(const unsigned char* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

uint32_t readLe32(const unsigned char* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

void appendBe32(Bytes& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<unsigned char>(v >> s));
}

// ---- OpenEXR ----------------------------------------------------------------------------------

void writeExr(const std::string& path, const Image& image, const ImageMetadata& metadata) {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    static const char* const kReserved[] = {"tiles",   "type",       "name",
                                            "version", "chunkCount", "maxSamplesPerPixel",
                                            "view",    "multiView"};
    for (const auto& [key, value] : metadata.entries) {
        bool reserved = false;
        for (const char* r : kReserved) reserved = reserved || key == r;
        if (key.empty() || reserved || header.find(key) != header.end())
            throw Error(path, 0, "metadata key '" + key + "' is empty or a reserved EXR attribute");
        header.insert(key, Imf::StringAttribute(value));
    }
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float), ys = xs * size_t(image.width);
    const char* base = reinterpret_cast<const char*>(image.rgb.data());
    fb.insert("R", Imf::Slice(Imf::FLOAT, const_cast<char*>(base + 0), xs, ys));
    fb.insert("G", Imf::Slice(Imf::FLOAT, const_cast<char*>(base + 4), xs, ys));
    fb.insert("B", Imf::Slice(Imf::FLOAT, const_cast<char*>(base + 8), xs, ys));
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
}

/// Bytes OpenEXR reads for an attribute of a fixed-size type whatever size the file gives, or -1.
int64_t exrFixedAttributeSize(const std::string& type) {
    static const std::pair<const char*, int> kSizes[] = {
        {"box2i", 16}, {"box2f", 16}, {"v2i", 8},  {"v2f", 8},  {"v2d", 16},
        {"v3i", 12},   {"v3f", 12},   {"v3d", 24}, {"m33f", 36}, {"m33d", 72},
        {"m44f", 64},  {"m44d", 128}, {"int", 4},  {"float", 4}, {"double", 8},
        {"compression", 1}, {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1},
        {"tiledesc", 9}, {"rational", 8}, {"keycode", 28}, {"timecode", 8},
        {"chromaticities", 32}};
    for (const auto& [name, bytes] : kSizes)
        if (type == name) return bytes;
    return -1;
}

/// Scan lines per chunk for an EXR compression method (Imf::Compression's values); 256, the most,
/// for values OpenEXR does not know (it refuses them), so that chunk counts stay lower bounds.
uint64_t exrLinesPerChunk(int compression) {
    switch (compression) {
        case Imf::NO_COMPRESSION:
        case Imf::RLE_COMPRESSION:
        case Imf::ZIPS_COMPRESSION:
            return 1;
        case Imf::ZIP_COMPRESSION:
        case Imf::PXR24_COMPRESSION:
            return 16;
        case Imf::PIZ_COMPRESSION:
        case Imf::B44_COMPRESSION:
        case Imf::B44A_COMPRESSION:
        case Imf::DWAA_COMPRESSION:
            return 32;
        default:
            return 256;  // DWAB
    }
}

/// The most bytes one uncompressed EXR chunk (lines per chunk x bytes per line, or a tile) may
/// hold: OpenEXR allocates buffers of that size, several, on opening a file, and a few header
/// bytes can claim any width (found by fuzzing: an 8386820 x 3 window of 3 half channels, within
/// kMaxImagePixels, made it allocate 800 MB buffers). Generous: 16 lines of 4 floats, 2^20 wide.
constexpr double kMaxExrChunkBytes = 256.0 * 1024 * 1024;

/// Where an EXR file's header(s) end (its first chunk offset table starts there), and whether
/// it is a multi-part file.
struct ExrLayout {
    uint64_t headerEnd = 0;
    bool multipart = false;
};

/// Walks the EXR header(s) before OpenEXR sees the file: OpenEXR allocates an attribute's value
/// with the size the file claims before reading it, so a few bytes claiming a 2 GB attribute
/// would cost 2 GB. Refuses attributes larger than what is left of the file (found by fuzzing).
/// Opening a file also sizes tables and buffers by the data window (found by fuzzing: a
/// 591-byte file with an 8847364 x 513 window cost seconds), so before OpenEXR opens it the
/// window must pass checkSize, its chunks' offset table must fit in the file, and one chunk (what
/// OpenEXR's line buffer and decompressor hold) must stay within kMaxExrChunkBytes.
ExrLayout checkExrHeader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, 0, "cannot open file for reading (missing or unreadable)");
    std::error_code ec;
    const uint64_t fileSize = std::filesystem::file_size(path, ec);
    if (ec) throw Error(path, 0, "cannot determine the file size");
    unsigned char head[8];
    if (!in.read(reinterpret_cast<char*>(head), 8))
        throw Error(path, 0, "corrupt header: the file is too short to be an EXR image");
    if (head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 || head[3] != 0x01)
        throw Error(path, 0, "corrupt header: not an OpenEXR file (bad magic number)");
    const bool multipart = (head[5] & 0x10) != 0;    // version flags, bit 12
    const bool singleTiled = (head[5] & 0x02) != 0;  // bit 9 (multi-part files: 'tiles' says)
    auto readName = [&](std::string& out) {
        out.clear();
        for (char c; in.get(c);) {
            if (c == '\0') return;
            if (out.size() >= 255) throw Error(path, 0, "corrupt header: attribute name too long");
            out.push_back(c);
        }
        throw Error(path, 0, "truncated header");
    };
    std::string name, type;
    uint64_t chunks = 0;  // a lower bound on the chunk offsets of the parts read so far
    auto layout = [&](bool multi) {
        const uint64_t end = uint64_t(in.tellg());
        if (chunks > (fileSize - std::min(end, fileSize)) / 8)
            throw Error(path, 0,
                        "corrupt or truncated data: the header needs a table of " +
                            std::to_string(chunks) + " chunk offsets, more than the file holds");
        return ExrLayout{end, multi};
    };
    for (bool firstHeader = true;; firstHeader = false) {
        readName(name);
        if (name.empty()) {
            if (firstHeader) throw Error(path, 0, "corrupt header: empty header");
            return layout(true);  // the empty header ending a multi-part list
        }
        // What OpenEXR sizes its tables by (its defaults: a 64 x 64 window, ZIP compression).
        int32_t window[4] = {0, 0, 63, 63};
        int compression = Imf::ZIP_COMPRESSION;
        uint32_t tile[2] = {0, 0};  // tiled parts: tile width and height
        int64_t chunkCount = 0;
        std::vector<std::pair<int, int32_t>> pixelBytes;  // per channel: bytes, x sampling
        for (; !name.empty(); readName(name)) {
            readName(type);
            unsigned char sz[4];
            if (!in.read(reinterpret_cast<char*>(sz), 4)) throw Error(path, 0, "truncated header");
            const int32_t size = int32_t(readLe32(sz));
            const uint64_t pos = uint64_t(in.tellg());
            if (size < 0 || uint64_t(size) > fileSize - std::min(pos, fileSize))
                throw Error(path, 0,
                            "corrupt header: attribute '" + name + "' claims " +
                                std::to_string(size) + " bytes, more than the file holds");
            // OpenEXR reads fixed-size types and channel lists by their type, not by `size`:
            // follow it so that this walk stays where OpenEXR is.
            if (type == "chlist") {  // name, then pixel type, flags, x and y sampling
                std::string channel;
                pixelBytes.clear();
                for (readName(channel); !channel.empty(); readName(channel)) {
                    unsigned char c[16];
                    if (!in.read(reinterpret_cast<char*>(c), 16))
                        throw Error(path, 0, "truncated header");
                    pixelBytes.push_back(
                        {readLe32(c) == Imf::HALF ? 2 : 4, std::max(int32_t(readLe32(c + 8)), 1)});
                }
                continue;
            }
            auto readU32 = [&] {
                unsigned char b[4];
                if (!in.read(reinterpret_cast<char*>(b), 4)) throw Error(path, 0, "truncated header");
                return readLe32(b);
            };
            auto refuse = [&] {
                throw Error(path, 0, "corrupt header: attribute '" + name + "' (" + type +
                                         ") holds more than the file does");
            };
            if (type == "preview") {  // width, height, then 4 bytes per pixel, allocated first
                const uint64_t w = readU32(), h = readU32();
                if (w * h > (fileSize - std::min(uint64_t(in.tellg()), fileSize)) / 4) refuse();
                in.seekg(int64_t(w * h * 4), std::ios::cur);
                continue;
            }
            if (type == "stringvector") {  // (length, bytes) pairs, each length allocated first
                const uint64_t end = pos + uint64_t(size);
                while (uint64_t(in.tellg()) < end) {
                    const uint32_t n = readU32();
                    if (uint64_t(in.tellg()) + n > end) refuse();
                    in.seekg(n, std::ios::cur);
                }
                continue;
            }
            const int64_t fixed = exrFixedAttributeSize(type);
            if (fixed > 0 && fixed <= 16) {  // small fixed-size values: read, keep those above
                unsigned char v[16];
                if (!in.read(reinterpret_cast<char*>(v), fixed))
                    throw Error(path, 0, "truncated header");
                if (name == "dataWindow" && type == "box2i")
                    for (int k = 0; k < 4; ++k) window[k] = int32_t(readLe32(v + 4 * k));
                else if (name == "compression" && type == "compression")
                    compression = v[0];
                else if (name == "tiles" && type == "tiledesc")
                    tile[0] = readLe32(v), tile[1] = readLe32(v + 4);
                else if (name == "chunkCount" && type == "int")
                    chunkCount = std::max(int32_t(readLe32(v)), 0);
                continue;
            }
            in.seekg(fixed >= 0 ? fixed : size, std::ios::cur);
        }
        const int64_t w = int64_t(window[2]) - window[0] + 1,
                      h = int64_t(window[3]) - window[1] + 1;
        checkSize(path, w, h);
        const bool tiled = tile[0] && tile[1] && (multipart || singleTiled);
        double lineBytes = 0;  // of a chunk's width: the data window's, or a tile's
        for (const auto& [bytes, xSampling] : pixelBytes)
            lineBytes += double(bytes) * std::ceil(double(tiled ? tile[0] : w) / xSampling);
        const double chunkBytes =
            lineBytes * (tiled ? double(tile[1]) : double(exrLinesPerChunk(compression)));
        if (chunkBytes > kMaxExrChunkBytes)
            throw Error(path, 0,
                        "corrupt header: one chunk of the image (" +
                            (tiled ? "a tile of " + std::to_string(tile[0]) + " x " +
                                         std::to_string(tile[1]) + " pixels"
                                   : std::to_string(exrLinesPerChunk(compression)) +
                                         " scan lines " + std::to_string(w) + " pixels wide") +
                            ") would take " + std::to_string(int64_t(chunkBytes / 1048576)) +
                            " MiB, more than the 256 MiB caustica reads");
        // Scan lines: one offset per chunk of lines; tiles: at least those of level 0. OpenEXR
        // allocates both this and the chunkCount it is given, so the larger must fit.
        const uint64_t perWindow =
            tiled
                ? ((uint64_t(w) + tile[0] - 1) / tile[0]) * ((uint64_t(h) + tile[1] - 1) / tile[1])
                : (uint64_t(h) + exrLinesPerChunk(compression) - 1) / exrLinesPerChunk(compression);
        chunks += std::max(perWindow, uint64_t(chunkCount));
        if (!multipart) return layout(false);
    }
}

/// Chunks (blocks of scan lines, or tiles) in the offset table of the part `header` describes.
uint64_t exrChunkCount(const std::string& path, const Imf::Header& header) {
    if (header.hasChunkCount()) return uint64_t(std::max(header.chunkCount(), 0));
    if (header.hasTileDescription()) {
        Imf::TiledInputFile tiled(path.c_str());
        uint64_t n = 0;  // mip-map levels are (l, l), rip-map levels every (lx, ly)
        for (int ly = 0; ly < tiled.numYLevels(); ++ly)
            for (int lx = 0; lx < tiled.numXLevels(); ++lx)
                if (lx == ly || tiled.levelMode() == Imf::RIPMAP_LEVELS)
                    n += uint64_t(tiled.numXTiles(lx)) * uint64_t(tiled.numYTiles(ly));
        return n;
    }
    const uint64_t lines = exrLinesPerChunk(header.compression());
    const Imath::Box2i dw = header.dataWindow();
    return (uint64_t(int64_t(dw.max.y) - dw.min.y + 1) + lines - 1) / lines;
}

/// Refuses an EXR file whose chunks do not all lie within the file (`parts`: the header of each
/// part, in order). OpenEXR 3.1 throws when it reads past the end, but not every version does:
/// some fill what is missing of a file cut short (uncompressed, say) with zeros without a word.
/// Parts holding deep data are not followed (readImage refuses them).
void checkExrChunks(const std::string& path, const std::vector<Imf::Header>& parts,
                    const ExrLayout& layout) {
    const uint64_t fileSize = std::filesystem::file_size(path);
    std::vector<uint64_t> counts;  // the parts' offset tables follow one another
    uint64_t total = 0;
    for (const Imf::Header& header : parts) {
        counts.push_back(exrChunkCount(path, header));
        total += counts.back();
        if (total > fileSize / 8) break;
    }
    const uint64_t tableEnd = layout.headerEnd + 8 * total;
    if (total > fileSize / 8 || tableEnd > fileSize)
        throw Error(path, 0, "truncated data: the file ends inside its table of chunk offsets");
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> table(8 * total);
    in.seekg(std::streamoff(layout.headerEnd));
    if (!in.read(reinterpret_cast<char*>(table.data()), std::streamsize(table.size())))
        throw Error(path, 0, "read error");
    const unsigned char* next = table.data();
    for (size_t p = 0; p < parts.size(); ++p) {
        const Imf::Header& header = parts[p];
        const bool deep = header.hasType() && header.type().rfind("deep", 0) == 0;
        // A chunk: [part number], y or 4 tile coordinates, data size (4 bytes each), data.
        const uint64_t prefix = (layout.multipart ? 4 : 0) + (header.hasTileDescription() ? 20 : 8);
        for (uint64_t i = 0; i < counts[p]; ++i, next += 8) {
            const uint64_t offset = uint64_t(readLe32(next)) | uint64_t(readLe32(next + 4)) << 32;
            if (deep) continue;
            const std::string chunk = "chunk " + std::to_string(i) + " of " +
                                      std::to_string(counts[p]) +
                                      (layout.multipart ? " in part " + std::to_string(p) : "");
            const std::string file = "the file has " + std::to_string(fileSize) + " bytes";
            if (offset < tableEnd || offset > fileSize || fileSize - offset < prefix)
                throw Error(path, 0,
                            "truncated or incomplete data: " + chunk + " is missing (offset " +
                                std::to_string(offset) + ", " + file + ")");
            unsigned char size[4];
            in.seekg(std::streamoff(offset + prefix - 4));
            if (!in.read(reinterpret_cast<char*>(size), 4)) throw Error(path, 0, "read error");
            const uint64_t end = offset + prefix + readLe32(size);
            if (int32_t(readLe32(size)) < 0 || end > fileSize)
                throw Error(path, 0,
                            "truncated data: " + chunk + " ends at byte " + std::to_string(end) +
                                ", past the end of the file (" + file + ")");
        }
    }
}

/// The header of each part of an EXR file (`file`'s alone when it has one part).
std::vector<Imf::Header> exrPartHeaders(const std::string& path, const Imf::InputFile& file,
                                        const ExrLayout& layout) {
    if (!layout.multipart) return {file.header()};
    Imf::MultiPartInputFile multipart(path.c_str());
    std::vector<Imf::Header> headers;
    for (int i = 0; i < multipart.parts(); ++i) headers.push_back(multipart.header(i));
    return headers;
}

/// What must hold before OpenEXR allocates for `file`'s pixels: a sane data window, a complete
/// file, every chunk inside it (found by fuzzing: a 434-byte file without its chunks made it
/// allocate and clear 1.7 GB for a 262148 x 549 window).
void checkExrData(const std::string& path, const Imf::InputFile& file, const ExrLayout& layout) {
    const Imath::Box2i dw = file.header().dataWindow();
    checkSize(path, int64_t(dw.max.x) - dw.min.x + 1, int64_t(dw.max.y) - dw.min.y + 1);
    if (!file.isComplete()) throw Error(path, 0, "truncated data: the file is incomplete");
    checkExrChunks(path, exrPartHeaders(path, file, layout), layout);
}

Image readExr(const std::string& path) {
    requireReadable(path);
    const ExrLayout layout = checkExrHeader(path);
    Imf::InputFile file(path.c_str());
    checkExrData(path, file, layout);
    const Imath::Box2i dw = file.header().dataWindow();
    const int64_t w = int64_t(dw.max.x) - dw.min.x + 1, h = int64_t(dw.max.y) - dw.min.y + 1;
    const Imf::ChannelList& channels = file.header().channels();
    const bool rgb =
        channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    const bool grey = channels.findChannel("Y") != nullptr;
    if (!rgb && grey && (channels.findChannel("RY") || channels.findChannel("BY")))
        throw Error(path, 0, "luminance/chroma (Y, RY, BY) EXR images are not supported");
    if (!rgb && !grey) {
        std::string names;
        for (auto it = channels.begin(); it != channels.end(); ++it)
            names += std::string(names.empty() ? "" : ", ") + it.name();
        throw Error(path, 0, "no R, G, B or Y channels (found: " + names + ")");
    }
    Image image{int(w), int(h)};
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float);
    char* base = reinterpret_cast<char*>(image.rgb.data());
    if (rgb) {
        fb.insert("R", Imf::Slice::Make(Imf::FLOAT, base + 0, dw, xs, xs * size_t(w)));
        fb.insert("G", Imf::Slice::Make(Imf::FLOAT, base + 4, dw, xs, xs * size_t(w)));
        fb.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 8, dw, xs, xs * size_t(w)));
    } else {
        fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, base, dw, xs, xs * size_t(w)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (!rgb)
        for (size_t i = 0; i < image.pixelCount(); ++i)
            image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = image.rgb[3 * i];
    return image;
}

ImageMetadata readExrMetadata(const std::string& path) {
    requireReadable(path);
    checkExrHeader(path);
    Imf::InputFile file(path.c_str());
    ImageMetadata metadata;
    for (auto it = file.header().begin(); it != file.header().end(); ++it)
        if (std::strcmp(it.attribute().typeName(), Imf::StringAttribute::staticTypeName()) == 0)
            metadata.entries[it.name()] =
                static_cast<const Imf::StringAttribute&>(it.attribute()).value();
    return metadata;
}

// ---- PFM --------------------------------------------------------------------------------------

float toLittleEndianFloat(float v, bool swap) {
    if (!swap) return v;
    uint32_t u;
    std::memcpy(&u, &v, 4);
    u = (u >> 24) | ((u >> 8) & 0xff00u) | ((u << 8) & 0xff0000u) | (u << 24);
    std::memcpy(&v, &u, 4);
    return v;
}

void writePfm(const std::string& path, const Image& image) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(path, 0, "cannot open file for writing");
    out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
    const bool swap = std::endian::native == std::endian::big;
    std::vector<float> row(3 * size_t(image.width));
    for (int y = image.height - 1; y >= 0; --y) {  // PFM stores the bottom row first
        const float* src = image.pixel(0, y);
        for (size_t i = 0; i < row.size(); ++i) row[i] = toLittleEndianFloat(src[i], swap);
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * 4));
    }
    out.close();
    if (!out) throw Error(path, 0, "write error");
}

Image readPfm(const std::string& path) {
    const Bytes data = readFile(path);
    size_t pos = 0;
    // Header: three whitespace-separated tokens after the type, then exactly one whitespace.
    auto token = [&](const char* what) {
        while (pos < data.size() && std::isspace(data[pos])) ++pos;
        std::string t;
        while (pos < data.size() && !std::isspace(data[pos]) && t.size() < 64)
            t += char(data[pos++]);
        if (t.empty() || pos >= data.size() || !std::isspace(data[pos]))
            throw Error(path, 0, std::string("corrupt header: bad or missing ") + what);
        return t;
    };
    if (data.size() < 2 || data[0] != 'P' || (data[1] != 'F' && data[1] != 'f'))
        throw Error(path, 0, "corrupt header: not a PFM file (expected 'PF' or 'Pf')");
    const int channels = data[1] == 'F' ? 3 : 1;
    pos = 2;
    if (pos >= data.size() || !std::isspace(data[pos]))
        throw Error(path, 0, "corrupt header: not a PFM file (expected 'PF' or 'Pf')");
    auto number = [&](const std::string& t, const char* what) {
        char* end = nullptr;
        const double v = std::strtod(t.c_str(), &end);
        if (end != t.c_str() + t.size() || !std::isfinite(v))
            throw Error(path, 0, std::string("corrupt header: bad ") + what + " '" + t + "'");
        return v;
    };
    const double w = number(token("width"), "width"), h = number(token("height"), "height");
    const double scale = number(token("scale"), "scale");
    ++pos;  // the single whitespace character before the raster
    // In range before the conversions below (found by fuzzing: a height of -5.2e29).
    if (w != std::floor(w) || h != std::floor(h) || w < 0 || h < 0 || w > 1e9 || h > 1e9)
        throw Error(path, 0, "corrupt header: bad image size");
    checkSize(path, int64_t(w), int64_t(h));
    if (scale == 0) throw Error(path, 0, "corrupt header: scale must not be 0");
    const size_t width = size_t(w), height = size_t(h), rowFloats = width * size_t(channels);
    const size_t need = rowFloats * height * 4;
    if (data.size() - pos < need)
        throw Error(path, 0,
                    "truncated data: " + std::to_string(data.size() - pos) +
                        " bytes of pixels, expected " + std::to_string(need));
    const bool swap = (scale < 0) != (std::endian::native == std::endian::little);
    const float mul = float(std::fabs(scale));
    Image image{int(width), int(height)};
    for (size_t fy = 0; fy < height; ++fy) {
        float* dst = image.pixel(0, int(height - 1 - fy));
        for (size_t x = 0; x < width; ++x) {
            for (int c = 0; c < 3; ++c) {
                const size_t i = fy * rowFloats + x * size_t(channels) + size_t(c % channels);
                float v;
                std::memcpy(&v, data.data() + pos + 4 * i, 4);
                v = toLittleEndianFloat(v, swap);
                dst[3 * x + size_t(c)] = mul == 1.0f ? v : v * mul;
            }
        }
    }
    return image;
}

// ---- PNG --------------------------------------------------------------------------------------

uint32_t crc32(const unsigned char* p, size_t n, uint32_t crc = 0) {
    crc = ~crc;
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

bool validPngKeyword(const std::string& k) {
    // PNG 11.3.4.3: 1-79 Latin-1 printable characters, no leading/trailing/double spaces.
    if (k.empty() || k.size() > 79 || k.front() == ' ' || k.back() == ' ') return false;
    for (size_t i = 0; i < k.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(k[i]);
        if (c < 32 || (c > 126 && c < 161)) return false;
        if (c == ' ' && i > 0 && k[i - 1] == ' ') return false;
    }
    return true;
}

void writePng(const std::string& path, const Image& image, const ImageMetadata& metadata) {
    std::vector<unsigned char> pixels(image.rgb.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = static_cast<unsigned char>(std::lround(linearToSrgb(image.rgb[i]) * 255.0f));
    Bytes png;
    auto sink = [](void* ctx, void* data, int size) {
        auto* out = static_cast<Bytes*>(ctx);
        const auto* p = static_cast<const unsigned char*>(data);
        out->insert(out->end(), p, p + size);
    };
    if (!stbi_write_png_to_func(sink, &png, image.width, image.height, 3, pixels.data(),
                                3 * image.width) ||
        png.size() < 33)
        throw Error(path, 0, "PNG encoding failed");
    // tEXt chunks go right after the signature (8 bytes) and IHDR (25 bytes).
    Bytes text;
    for (const auto& [key, value] : metadata.entries) {
        if (!validPngKeyword(key) || value.find('\0') != std::string::npos)
            throw Error(path, 0, "metadata key '" + key + "' is not a valid PNG text keyword");
        Bytes chunk = {'t', 'E', 'X', 't'};
        chunk.insert(chunk.end(), key.begin(), key.end());
        chunk.push_back(0);
        chunk.insert(chunk.end(), value.begin(), value.end());
        appendBe32(text, uint32_t(chunk.size() - 4));
        text.insert(text.end(), chunk.begin(), chunk.end());
        appendBe32(text, crc32(chunk.data(), chunk.size()));
    }
    png.insert(png.begin() + 33, text.begin(), text.end());
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(path, 0, "cannot open file for writing");
    out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    out.close();
    if (!out) throw Error(path, 0, "write error");
}

/// The w x h image of stb's interleaved RGB samples `pixels` (8 or 16 bits), scaled to [0, 1] by
/// `maxValue` and decoded from sRGB to linear unless `raw`.
template <class T>
Image imageFromStb(const T* pixels, int w, int h, float maxValue, bool raw) {
    Image image(w, h);
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        const float v = float(pixels[i]) / maxValue;
        image.rgb[i] = raw ? v : srgbToLinear(v);
    }
    return image;
}

const Bytes kPngMagic = {137, 80, 78, 71, 13, 10, 26, 10};
const Bytes kJpegMagic = {0xFF, 0xD8, 0xFF};

/// Calls `f(type, body, length)` for each chunk of the PNG file `data` up to IEND, refusing a chunk
/// whose length (data, then a 4-byte CRC) runs past the end of the file or PNG's limit of 2^31-1:
/// stb allocates a chunk's claimed length before reading it (found by fuzzing: a 103-byte PNG
/// cost 2 GiB). A file ending after complete chunks without IEND is left to the decoder.
template <class F>
void forEachPngChunk(const std::string& path, const Bytes& data, F&& f) {
    if (data.size() < 8 || !std::equal(kPngMagic.begin(), kPngMagic.end(), data.begin()))
        throw Error(path, 0, "corrupt header: not a PNG file");
    for (size_t pos = 8; pos + 8 <= data.size();) {
        const uint32_t length = readBe32(&data[pos]);
        std::string type;
        for (size_t i = pos + 4; i < pos + 8; ++i) {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02x", data[i]);
            type += std::isalpha(data[i]) ? std::string(1, char(data[i])) : hex;
        }
        const size_t left = data.size() - pos - 8;
        if (length > 0x7fffffffu || size_t(length) + 4 > left)
            throw Error(path, 0,
                        "corrupt or truncated data: PNG chunk '" + type + "' length " +
                            std::to_string(length) + " (+ 4 bytes CRC) exceeds the " +
                            std::to_string(left) + " bytes left in the file");
        f(type, &data[pos + 8], size_t(length));
        if (type == "IEND") return;
        pos += 12 + size_t(length);
    }
}

/// PNG or JPEG (`format`; 8 or 16 bits per channel, sRGB-encoded) via stb; decoded to linear
/// unless `raw`.
/// Walks a JPEG's marker segments where stb_image reads them and refuses what this stb (Debian's
/// libstb 0.0~git20220908, not instrumented) would read or write out of bounds or uninitialised:
/// a Huffman table of more than 256 symbols (stb fills arrays of 256), and a scan using a Huffman
/// or quantisation table that no DHT or DQT segment defined before it (found by fuzzing: stb
/// decoded with the garbage its malloc held, and an assertion in stbi__jpeg_huff_decode aborted).
/// It also refuses a scan whose data cannot hold its blocks (a baseline block takes at least 2
/// bits, a first DC scan's 1): stb decodes what is missing as zeros, so 24 bytes could make it
/// decode a 13156 x 4214 image (found by fuzzing: a 5 s timeout under ASan).
/// Where stb would refuse the file anyway the walk stops and leaves the refusal to stb.
void checkJpegTables(const std::string& path, const Bytes& data) {
    auto at = [&](size_t i) -> int { return i < data.size() ? data[i] : 0; };  // stb reads 0 at EOF
    bool dc[4] = {}, ac[4] = {}, quant[4] = {};
    int progressive = -1;  // until the frame header (SOF0/1: 0, SOF2: 1)
    struct Component {
        int id, h, v, quant;  // id, sampling factors, quantisation table
    };
    std::vector<Component> comps;  // the frame's
    uint64_t width = 0, height = 0;
    int hMax = 1, vMax = 1;
    auto refuse = [&](const std::string& what) {
        throw Error(path, 0, "corrupt data: JPEG " + what);
    };
    for (size_t pos = 2; pos < data.size();) {  // after SOI
        if (data[pos] != 0xff) {  // stb skips bytes up to a marker (or refuses the file)
            ++pos;
            continue;
        }
        while (pos < data.size() && data[pos] == 0xff) ++pos;  // fill bytes
        const int m = at(pos);
        const size_t seg = pos + 1, len = size_t(at(seg) << 8 | at(seg + 1));  // len counts itself
        if (m == 0xc4 || m == 0xdb) {  // DHT, DQT: tables until the length is used up, as stb
            for (long left = long(len) - 2, p = long(seg) + 2; left > 0;) {
                const int q = at(size_t(p)), hi = q >> 4, t = q & 15;
                if (hi > 1 || t > 3) return;
                long size = 1 + (hi ? 128 : 64);
                if (m == 0xc4) {
                    long n = 0;
                    for (int i = 1; i <= 16; ++i) n += at(size_t(p + i));
                    if (n > 256)
                        refuse("Huffman table with " + std::to_string(n) +
                               " symbols (at most 256)");
                    (hi ? ac : dc)[t] = true;
                    size = 17 + n;
                } else {
                    quant[t] = true;
                }
                p += size;
                left -= size;
            }
        } else if (m == 0xc0 || m == 0xc1 || m == 0xc2) {  // the frame (a second one: stb refuses)
            if (progressive >= 0) return;
            progressive = m == 0xc2;
            height = uint64_t(at(seg + 3) << 8 | at(seg + 4));
            width = uint64_t(at(seg + 5) << 8 | at(seg + 6));
            for (int i = 0, n = at(seg + 7); i < n; ++i) {
                const size_t c = seg + 8 + 3 * size_t(i);
                const int h = at(c + 1) >> 4, v = at(c + 1) & 15;
                if (h < 1 || h > 4 || v < 1 || v > 4) return;  // stb refuses these
                comps.push_back({at(c), h, v, at(c + 2)});
                hMax = std::max(hMax, h);
                vMax = std::max(vMax, v);
            }
        } else if (m == 0xda) {  // a scan: the tables it decodes with must be defined by now
            if (progressive < 0) return;
            const int n = at(seg + 2), spectralStart = at(seg + 3 + 2 * size_t(n));
            const bool firstDc = spectralStart == 0 && at(seg + 5 + 2 * size_t(n)) >> 4 == 0;
            auto blocksAcross = [](uint64_t pixels, int f, int fMax) {
                return ((pixels * uint64_t(f) + uint64_t(fMax) - 1) / uint64_t(fMax) + 7) / 8;
            };
            const uint64_t mcus = blocksAcross(width, 1, hMax) * blocksAcross(height, 1, vMax);
            uint64_t blocks = 0;
            for (int i = 0; i < n; ++i) {
                const int id = at(seg + 3 + 2 * size_t(i)), t = at(seg + 4 + 2 * size_t(i));
                const auto c = std::find_if(comps.begin(), comps.end(),
                                            [&](const Component& x) { return x.id == id; });
                if (c == comps.end() || c->quant > 3 || t >> 4 > 3 || (t & 15) > 3) return;
                // One component: its own blocks; several: MCUs times each one's h x v blocks.
                blocks += n == 1
                              ? blocksAcross(width, c->h, hMax) * blocksAcross(height, c->v, vMax)
                              : mcus * uint64_t(c->h * c->v);
                if (!quant[c->quant])
                    refuse("scan uses quantisation table " + std::to_string(c->quant) +
                           ", which no DQT segment defines before it");
                if ((!progressive || spectralStart == 0) && !dc[t >> 4])
                    refuse("scan uses DC Huffman table " + std::to_string(t >> 4) +
                           ", which no DHT segment defines before it");
                if ((!progressive || spectralStart > 0) && !ac[t & 15])
                    refuse("scan uses AC Huffman table " + std::to_string(t & 15) +
                           ", which no DHT segment defines before it");
            }
            // The entropy-coded data runs to the next marker other than 0xff00 (a stuffed 0xff)
            // or a restart marker.
            for (pos = seg + len; pos < data.size(); ++pos) {
                if (data[pos] != 0xff) continue;
                size_t q = pos + 1;
                while (q < data.size() && data[q] == 0xff) ++q;
                if (q < data.size() && data[q] != 0 && (data[q] < 0xd0 || data[q] > 0xd7)) break;
                pos = q;
            }
            const uint64_t bits = 8 * (std::max(pos, seg + len) - (seg + len));
            const uint64_t bitsPerBlock = !progressive ? 2 : firstDc ? 1 : 0;
            if (bits < bitsPerBlock * blocks)
                refuse("scan of " + std::to_string(blocks) + " blocks holds " +
                       std::to_string(bits / 8) + " bytes, less than " +
                       std::to_string(bitsPerBlock) + " bits per block (truncated or corrupt)");
            continue;
        } else if (!(m >= 0xe0 && m <= 0xef) && m != 0xfe && m != 0xdd && m != 0xdc) {
            return;  // end of image, or a marker stb refuses (SOF3 and up, restart outside a scan)
        }
        pos = seg + len;  // stb reads each segment to the end its length gives, or refuses it
    }
}

Image readLdr(const std::string& path, Format format, const ImageReadOptions& options,
              ImageFileInfo* info) {
    const Bytes data = readFile(path);
    if (data.size() > size_t(INT32_MAX)) throw Error(path, 0, "file too large");
    if (format == Format::Png) {
        forEachPngChunk(path, data, [](auto&&...) {});
    } else if (data.size() < kJpegMagic.size() ||
               !std::equal(kJpegMagic.begin(), kJpegMagic.end(), data.begin())) {
        throw Error(path, 0, "corrupt header: not a JPEG file");
    } else {
        checkJpegTables(path, data);
    }
    const int size = int(data.size());
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_memory(data.data(), size, &w, &h, &n))
        throw Error(path, 0, std::string("corrupt header: ") + stbReason());
    checkSize(path, w, h);
    // The image is allocated only once stb has decoded the pixels: a header alone may claim up
    // to kMaxImagePixels (found by fuzzing: an 86-byte PNG cost 1.6 GB and seconds).
    Image image;
    if (stbi_is_16_bit_from_memory(data.data(), size)) {
        std::unique_ptr<stbi_us, void (*)(void*)> p(
            stbi_load_16_from_memory(data.data(), size, &w, &h, &n, 3), stbi_image_free);
        if (!p) throw Error(path, 0, std::string("corrupt or truncated data: ") + stbReason());
        image = imageFromStb(p.get(), w, h, 65535.0f, options.raw);
        if (info) info->bitsPerChannel = 16;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> p(
            stbi_load_from_memory(data.data(), size, &w, &h, &n, 3), stbi_image_free);
        if (!p) throw Error(path, 0, std::string("corrupt or truncated data: ") + stbReason());
        image = imageFromStb(p.get(), w, h, 255.0f, options.raw);
        if (info) info->bitsPerChannel = 8;
    }
    if (info) info->channels = n;
    return image;
}

/// Radiance RGBE (.hdr): linear float RGB (hdr_reader.h; not stb, which hangs on some
/// truncated files).
Image readHdr(const std::string& path, ImageFileInfo* info) {
    Image image = decodeRadianceHdr(path, readFile(path));
    if (info) {
        info->bitsPerChannel = 32;
        info->channels = 3;
    }
    return image;
}

ImageMetadata readPngMetadata(const std::string& path) {
    ImageMetadata metadata;
    forEachPngChunk(
        path, readFile(path),
        [&](const std::string& type, const unsigned char* body, size_t length) {
            if (type != "tEXt") return;
            const auto* zero = static_cast<const unsigned char*>(std::memchr(body, 0, length));
            if (zero)
                metadata.entries[std::string(body, zero)] = std::string(zero + 1, body + length);
        });
    return metadata;
}

// Runs `body`, turning library exceptions into caustica::Error naming the file.
template <class F>
auto guarded(const std::string& path, F&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        std::string reason = e.what();  // the CLI prints errors on one line
        std::replace(reason.begin(), reason.end(), '\n', ' ');
        throw Error(path, 0, reason);
    }
}

}  // namespace

void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata) {
    const Format format = formatOf(path);
    if (image.width <= 0 || image.height <= 0 || image.rgb.size() != 3 * image.pixelCount())
        throw Error(path, 0,
                    "cannot write an empty or inconsistent image (" + std::to_string(image.width) +
                        " x " + std::to_string(image.height) + ", " +
                        std::to_string(image.rgb.size()) + " floats)");
    // Write under a temporary name (same extension, so format detection is unaffected), then
    // rename into place.
    const std::string tmp = path + ".partial" + std::filesystem::path(path).extension().string();
    guarded(path, [&] {
        try {
            switch (format) {
                case Format::Exr:
                    writeExr(tmp, image, metadata);
                    break;
                case Format::Pfm:
                    writePfm(tmp, image);
                    break;
                case Format::Png:
                    writePng(tmp, image, metadata);
                    break;
                case Format::Jpeg:
                case Format::Hdr:
                    throw Error(path, 0, "writing .jpg and .hdr images is not supported");
            }
            std::filesystem::rename(tmp, path);
        } catch (const Error& e) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw Error(path, 0, e.reason());
        } catch (...) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw;
        }
    });
}

Image readImage(const std::string& path) { return readImage(path, ImageReadOptions{}); }

Image readImage(const std::string& path, const ImageReadOptions& options, ImageFileInfo* info) {
    const Format format = formatOf(path);
    if (info) *info = ImageFileInfo{};
    return guarded(path, [&] {
        switch (format) {
            case Format::Exr:
                return readExr(path);
            case Format::Pfm:
                return readPfm(path);
            case Format::Png:
                return readLdr(path, format, options, info);
            case Format::Jpeg:
                return readLdr(path, format, options, info);
            case Format::Hdr:
                return readHdr(path, info);
        }
        return Image();
    });
}

void checkExrFile(const std::string& path) {
    guarded(path, [&] {
        requireReadable(path);
        const ExrLayout layout = checkExrHeader(path);
        Imf::InputFile file(path.c_str());
        checkExrData(path, file, layout);
    });
}

ImageMetadata readImageMetadata(const std::string& path) {
    const Format format = formatOf(path);
    return guarded(path, [&] {
        switch (format) {
            case Format::Exr:
                return readExrMetadata(path);
            case Format::Pfm:
                requireReadable(path);
                return ImageMetadata();
            case Format::Png:
                return readPngMetadata(path);
            case Format::Jpeg:
            case Format::Hdr:
                requireReadable(path);
                return ImageMetadata();
        }
        return ImageMetadata();
    });
}

bool isExrPath(const std::string& path) { return lowerExtension(path) == "exr"; }

}  // namespace caustica
