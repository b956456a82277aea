// exr_feature_layers.cpp — reading AOV layers by type with OpenEXR's scan-line API.
#include "caustica/io/exr_feature_layers.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <exception>
#include <sstream>

#include "caustica/util/error.h"

namespace caustica {

namespace {

/// Reads channels NAME.suffix[k] into channel k of an RGB image; one suffix fills R, G and B.
Image readLayer(Imf::InputFile& file, const std::string& path, const std::string& name,
                const std::vector<const char*>& suffixes) {
    const Imath::Box2i dw = file.header().dataWindow();
    const int width = dw.max.x - dw.min.x + 1, height = dw.max.y - dw.min.y + 1;
    Image image(width, height);
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float), ys = xs * size_t(width);
    char* base = reinterpret_cast<char*>(image.rgb.data()) - (ptrdiff_t(dw.min.x) * ptrdiff_t(xs)) -
                 ptrdiff_t(dw.min.y) * ptrdiff_t(ys);
    for (size_t k = 0; k < suffixes.size(); ++k) {
        const std::string channel = name + "." + suffixes[k];
        if (!file.header().channels().findChannel(channel))
            throw Error(path, 0, "AOV layer '" + name + "' lacks channel " + channel);
        fb.insert(channel, Imf::Slice(Imf::FLOAT, base + k * sizeof(float), xs, ys));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (suffixes.size() == 1)
        for (size_t i = 0; i < image.pixelCount(); ++i) image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = image.rgb[3 * i];
    return image;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> parseAovSpec(const std::string& spec) {
    std::vector<std::pair<std::string, std::string>> out;
    std::stringstream ss(spec);
    std::string item;
    while (std::getline(ss, item, ',')) {
        const size_t colon = item.find(':');
        if (colon == std::string::npos || colon == 0 || colon + 1 == item.size() ||
            item.find(':', colon + 1) != std::string::npos)
            throw Error("AOV spec entry '" + item + "' is not NAME:TYPE");
        out.emplace_back(item.substr(0, colon), item.substr(colon + 1));
    }
    return out;
}

DenoiseFeatures readFeatureLayers(const std::string& path) {
    DenoiseFeatures features;
    try {
        Imf::InputFile file(path.c_str());
        const auto* attr = file.header().findTypedAttribute<Imf::StringAttribute>(kAovsAttribute);
        if (!attr) return features;
        std::string geoNormal;
        for (const auto& [name, type] : parseAovSpec(attr->value())) {
            if (type == "albedo" && !features.albedo)
                features.albedo = readLayer(file, path, name, {"R", "G", "B"});
            else if (type == "sh_normal" && !features.normal)
                features.normal = readLayer(file, path, name, {"X", "Y", "Z"});
            else if (type == "geo_normal" && geoNormal.empty())
                geoNormal = name;
            else if (type == "depth" && !features.depth)
                features.depth = readLayer(file, path, name, {"T"});
            else if (type == "variance" && !features.variance)
                features.variance = readLayer(file, path, name, {"R", "G", "B"});
        }
        if (!features.normal && !geoNormal.empty()) features.normal = readLayer(file, path, geoNormal, {"X", "Y", "Z"});
    } catch (const Error& e) {
        if (!e.file().empty()) throw;
        throw Error(path, 0, e.reason());
    } catch (const std::exception& e) {
        throw Error(path, 0, std::string("cannot read AOV layers: ") + e.what());
    }
    return features;
}

}  // namespace caustica
