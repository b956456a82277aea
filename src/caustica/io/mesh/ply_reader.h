// ply_reader.h — the PLY header and the two ways of reading PLY element data (ascii tokens,
// binary bytes in either byte order). Errors are caustica::Error with an empty file name and the
// line where known; loadPly adds the file name.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace caustica::meshio {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

bool isIntegerType(PlyType t);
size_t typeSize(PlyType t);

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;  // list: type of the items
    bool isList = false;
    PlyType countType = PlyType::UInt8;  // list only
};

struct PlyElement {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProperty> properties;
    int line = 0;  // header line declaring it
};

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    size_t dataOffset = 0;  // first byte after "end_header\n"
    int dataLine = 0;       // line number of that byte (ascii)
    const PlyElement* find(std::string_view name) const {
        for (const PlyElement& e : elements)
            if (e.name == name) return &e;
        return nullptr;
    }
};

/// Parses the header at the start of `data` (the whole file).
PlyHeader parsePlyHeader(std::string_view data);

/// Reads ascii element data: one record per line, tokens separated by blanks.
class AsciiPlyReader {
public:
    AsciiPlyReader(std::string_view data, size_t offset, int firstLine);
    void beginRecord(const std::string& element, uint64_t index);
    double scalar(PlyType type, const std::string& property);
    uint64_t count(PlyType type, const std::string& property);
    void endRecord();
    void finish();
    uint64_t remaining() const { return data_.size() - pos_; }
    [[noreturn]] void fail(const std::string& reason) const;

private:
    std::string_view data_;
    size_t pos_;
    int line_;
    std::vector<std::string_view> tokens_;
    size_t next_ = 0;
    std::string element_;
    uint64_t index_ = 0;
};

/// Reads binary element data, swapping bytes when the file's byte order is not the host's.
class BinaryPlyReader {
public:
    BinaryPlyReader(std::string_view data, size_t offset, bool swap);
    void beginRecord(const std::string& element, uint64_t index);
    double scalar(PlyType type, const std::string& property);
    uint64_t count(PlyType type, const std::string& property);
    void endRecord() {}
    void finish() {}
    uint64_t remaining() const { return data_.size() - pos_; }
    [[noreturn]] void fail(const std::string& reason) const;

private:
    std::string_view data_;
    size_t pos_;
    bool swap_;
    std::string element_;
    uint64_t index_ = 0;
};

}  // namespace caustica::meshio
