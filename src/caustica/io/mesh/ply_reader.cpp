#include "caustica/io/mesh/ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "caustica/io/mesh/text_parse.h"
#include "caustica/util/error.h"

namespace caustica::meshio {

namespace {

bool typeFromName(std::string_view s, PlyType& t) {
    static const std::pair<const char*, PlyType> kNames[] = {
        {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto& [name, type] : kNames)
        if (s == name) {
            t = type;
            return true;
        }
    return false;
}

/// Value range of an integer type, to refuse ascii values that do not fit.
void integerRange(PlyType t, double& lo, double& hi) {
    switch (t) {
        case PlyType::Int8:
            lo = -128, hi = 127;
            break;
        case PlyType::UInt8:
            lo = 0, hi = 255;
            break;
        case PlyType::Int16:
            lo = -32768, hi = 32767;
            break;
        case PlyType::UInt16:
            lo = 0, hi = 65535;
            break;
        case PlyType::Int32:
            lo = -2147483648.0, hi = 2147483647.0;
            break;
        default:
            lo = 0, hi = 4294967295.0;
            break;
    }
}

const char* typeName(PlyType t) {
    static const char* kNames[] = {"char", "uchar", "short", "ushort",
                                   "int",  "uint",  "float", "double"};
    return kNames[int(t)];
}

/// The T stored in host byte order at `b`, as a double.
template <class T>
double loadAs(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return double(v);
}

}  // namespace

bool isIntegerType(PlyType t) {
    return t != PlyType::Float32 && t != PlyType::Float64;
}

size_t typeSize(PlyType t) {
    static const size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return kSizes[int(t)];
}

PlyHeader parsePlyHeader(std::string_view data) {
    PlyHeader h;
    size_t pos = 0;
    int line = 0;
    bool sawFormat = false;
    const char* const truncated =
        "PLY header truncated: no 'end_header' before the end of the file";
    while (true) {
        if (pos >= data.size()) throw Error("", line, truncated);
        size_t end = data.find('\n', pos);
        const bool lastLine = end == std::string_view::npos;
        if (lastLine) end = data.size();
        std::string_view l = data.substr(pos, end - pos);
        pos = std::min(end + 1, data.size());
        ++line;
        std::vector<std::string_view> tok = tokenize(l, " \t\r");
        // A file cut inside the header ends on a line that may be cut too: say so, rather than
        // what is wrong with the cut line.
        if (lastLine && line > 1 && (tok.empty() || tok[0] != "end_header"))
            throw Error("", line, truncated);
        if (line == 1) {
            if (tok.size() != 1 || tok[0] != "ply")
                throw Error("", 1, "not a PLY file (first line must be 'ply')");
            continue;
        }
        if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
        const std::string kw(tok[0]);
        if (kw == "format") {
            if (tok.size() != 3) throw Error("", line, "expected 'format <type> 1.0'");
            if (tok[1] == "ascii")
                h.format = PlyFormat::Ascii;
            else if (tok[1] == "binary_little_endian")
                h.format = PlyFormat::BinaryLittleEndian;
            else if (tok[1] == "binary_big_endian")
                h.format = PlyFormat::BinaryBigEndian;
            else
                throw Error("", line, "unknown PLY format " + quoteText(tok[1]));
            if (tok[2] != "1.0")
                throw Error("", line, "unsupported PLY version " + quoteText(tok[2]));
            sawFormat = true;
        } else if (kw == "element") {
            int64_t count = 0;
            if (tok.size() != 3 || !parseInt64(tok[2], count) || count < 0)
                throw Error("", line, "expected 'element <name> <count>'");
            for (const PlyElement& e : h.elements)
                if (e.name == tok[1])
                    throw Error("", line, "element " + quoteText(tok[1]) + " declared twice");
            h.elements.push_back({std::string(tok[1]), uint64_t(count), {}, line});
        } else if (kw == "property") {
            if (h.elements.empty()) throw Error("", line, "'property' before any 'element'");
            PlyProperty p;
            bool ok;
            if (tok.size() >= 2 && tok[1] == "list") {
                ok = tok.size() == 5 && typeFromName(tok[2], p.countType) &&
                     typeFromName(tok[3], p.type);
                if (ok && !isIntegerType(p.countType))
                    throw Error("", line, "list count type must be an integer type");
                p.isList = true;
                if (ok) p.name = std::string(tok[4]);
            } else {
                ok = tok.size() == 3 && typeFromName(tok[1], p.type);
                if (ok) p.name = std::string(tok[2]);
            }
            if (!ok)
                throw Error("", line,
                            "expected 'property <type> <name>' or 'property list "
                            "<count type> <item type> <name>' with known types");
            h.elements.back().properties.push_back(p);
        } else if (kw == "end_header") {
            if (!sawFormat) throw Error("", line, "PLY header has no 'format' line");
            h.dataOffset = pos;
            h.dataLine = line + 1;
            return h;
        } else {
            throw Error("", line, "unknown PLY header keyword " + quoteText(tok[0]));
        }
    }
}

AsciiPlyReader::AsciiPlyReader(std::string_view data, size_t offset, int firstLine)
    : data_(data), pos_(offset), line_(firstLine - 1) {}

void AsciiPlyReader::fail(const std::string& reason) const {
    throw Error("", line_, reason);
}

void AsciiPlyReader::beginRecord(const std::string& element, uint64_t index) {
    element_ = element;
    index_ = index;
    tokens_.clear();
    next_ = 0;
    while (tokens_.empty()) {
        if (pos_ >= data_.size())
            throw Error("", line_,
                        "file ends before element '" + element + "' " + std::to_string(index) +
                            " (header promises more)");
        size_t end = data_.find('\n', pos_);
        if (end == std::string_view::npos) end = data_.size();
        tokens_ = tokenize(data_.substr(pos_, end - pos_), " \t\r");
        pos_ = std::min(end + 1, data_.size());
        ++line_;
    }
}

double AsciiPlyReader::scalar(PlyType type, const std::string& property) {
    if (next_ >= tokens_.size())
        fail("element '" + element_ + "' " + std::to_string(index_) + ": missing value for '" +
             property + "'");
    std::string_view t = tokens_[next_++];
    double v = 0;
    if (isIntegerType(type)) {
        int64_t i = 0;
        double lo, hi;
        integerRange(type, lo, hi);
        if (!parseInt64(t, i) || double(i) < lo || double(i) > hi)
            fail("element '" + element_ + "' " + std::to_string(index_) + ": bad " +
                 typeName(type) + " value " + quoteText(t) + " for '" + property + "'");
        v = double(i);
    } else if (!parseDouble(t, v)) {
        fail("element '" + element_ + "' " + std::to_string(index_) + ": bad number " +
             quoteText(t) + " for '" + property + "' (NaN, infinity or not a number)");
    }
    return v;
}

uint64_t AsciiPlyReader::count(PlyType type, const std::string& property) {
    return uint64_t(scalar(type, property));  // count types are integer types (header check)
}

void AsciiPlyReader::endRecord() {
    if (next_ != tokens_.size())
        fail("element '" + element_ + "' " + std::to_string(index_) + ": " +
             std::to_string(tokens_.size() - next_) + " values too many");
}

void AsciiPlyReader::finish() {
    int line = line_ + 1;  // pos_ is at the start of the line after the last record
    for (size_t i = pos_; i < data_.size(); ++i) {
        if (data_[i] == '\n')
            ++line;
        else if (!std::isspace(static_cast<unsigned char>(data_[i])))
            throw Error("", line,
                        "unexpected data after the last element (header counts too small?)");
    }
}

BinaryPlyReader::BinaryPlyReader(std::string_view data, size_t offset, bool swap)
    : data_(data), pos_(offset), swap_(swap) {}

void BinaryPlyReader::fail(const std::string& reason) const {
    throw Error("", 0, reason);
}

void BinaryPlyReader::beginRecord(const std::string& element, uint64_t index) {
    element_ = element;
    index_ = index;
}

double BinaryPlyReader::scalar(PlyType type, const std::string& property) {
    const size_t n = typeSize(type);
    if (data_.size() - pos_ < n)
        fail("file ends inside element '" + element_ + "' " + std::to_string(index_) +
             " (property '" + property + "'; truncated file or wrong counts in the header)");
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, n);
    pos_ += n;
    if (swap_) std::reverse(b, b + n);
    switch (type) {
        case PlyType::Int8:
            return loadAs<int8_t>(b);
        case PlyType::UInt8:
            return loadAs<uint8_t>(b);
        case PlyType::Int16:
            return loadAs<int16_t>(b);
        case PlyType::UInt16:
            return loadAs<uint16_t>(b);
        case PlyType::Int32:
            return loadAs<int32_t>(b);
        case PlyType::UInt32:
            return loadAs<uint32_t>(b);
        case PlyType::Float32:
            return loadAs<float>(b);
        case PlyType::Float64:
            return loadAs<double>(b);
    }
    return 0;
}

uint64_t BinaryPlyReader::count(PlyType type, const std::string& property) {
    double c = scalar(type, property);
    if (c < 0)
        fail("element '" + element_ + "' " + std::to_string(index_) + ": negative list count");
    return uint64_t(c);
}

}  // namespace caustica::meshio
