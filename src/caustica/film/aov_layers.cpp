// aov_layers.cpp — the aovs string: parsing, channel names.
#include "caustica/film/aov_layers.h"

#include "caustica/util/error.h"

namespace caustica {

namespace {

struct TypeInfo {
    AovType type;
    const char* name;
    std::vector<std::string> suffixes;
};

const std::vector<TypeInfo>& typeTable() {
    static const std::vector<TypeInfo> table = {
        {AovType::Depth, "depth", {"T"}},
        {AovType::Position, "position", {"X", "Y", "Z"}},
        {AovType::Uv, "uv", {"U", "V"}},
        {AovType::GeoNormal, "geo_normal", {"X", "Y", "Z"}},
        {AovType::ShNormal, "sh_normal", {"X", "Y", "Z"}},
        {AovType::Albedo, "albedo", {"R", "G", "B"}},
        {AovType::PrimIndex, "prim_index", {"I"}},
        {AovType::ShapeIndex, "shape_index", {"I"}},
        {AovType::Variance, "variance", {"R", "G", "B"}},
    };
    return table;
}

const TypeInfo& info(AovType type) {
    return typeTable()[size_t(type)];
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::string knownTypes() {
    std::string out;
    for (const TypeInfo& t : typeTable()) out += (out.empty() ? "" : ", ") + std::string(t.name);
    return out;
}

}  // namespace

int aovChannelCount(AovType type) {
    return int(info(type).suffixes.size());
}
const char* aovTypeName(AovType type) {
    return info(type).name;
}
std::vector<std::string> aovChannelSuffixes(AovType type) {
    return info(type).suffixes;
}

std::string AovSpec::text() const {
    std::string out;
    for (const AovLayer& l : layers)
        out += (out.empty() ? "" : ",") + l.name + ":" + aovTypeName(l.type);
    return out;
}

std::vector<std::string> AovSpec::channelNames() const {
    std::vector<std::string> names;
    for (const AovLayer& l : layers)
        for (const std::string& s : aovChannelSuffixes(l.type)) names.push_back(l.name + "." + s);
    return names;
}

bool AovSpec::has(AovType type) const {
    for (const AovLayer& l : layers)
        if (l.type == type) return true;
    return false;
}

AovSpec parseAovSpec(const std::string& text, const std::string& where) {
    AovSpec spec;
    if (trim(text).empty())
        throw Error(where + ": the aovs list is empty (expected NAME:TYPE[,NAME:TYPE...])");
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string item = trim(text.substr(start, end - start));
        start = end + 1;
        const size_t colon = item.find(':');
        if (colon == std::string::npos || item.find(':', colon + 1) != std::string::npos)
            throw Error(where + ": aov '" + item + "' is not a NAME:TYPE pair");
        AovLayer layer;
        layer.name = trim(item.substr(0, colon));
        const std::string type = trim(item.substr(colon + 1));
        if (layer.name.empty() || type.empty())
            throw Error(where + ": aov '" + item + "' is not a NAME:TYPE pair");
        bool found = false;
        for (const TypeInfo& t : typeTable())
            if (type == t.name) {
                layer.type = t.type;
                found = true;
            }
        if (!found)
            throw Error(where + ": unknown AOV type '" + type + "' (known: " + knownTypes() + ")");
        if (layer.name == "R" || layer.name == "G" || layer.name == "B" || layer.name == "A")
            throw Error(where + ": aov name '" + layer.name +
                        "' is taken by the image's own channels");
        for (const AovLayer& l : spec.layers)
            if (l.name == layer.name)
                throw Error(where + ": aov name '" + layer.name + "' is given twice");
        spec.layers.push_back(layer);
        if (spec.layers.size() > size_t(kMaxAovLayers))
            throw Error(where + ": more than " + std::to_string(kMaxAovLayers) + " AOVs");
        if (end == text.size()) break;
    }
    return spec;
}

int AovImage::firstChannelOf(AovType type) const {
    int c = 0;
    for (const AovLayer& l : spec.layers) {
        if (l.type == type) return c;
        c += aovChannelCount(l.type);
    }
    return -1;
}

}  // namespace caustica
