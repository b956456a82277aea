// exr_layers.cpp — the image and its AOV layers in one OpenEXR file (OpenEXR 3).
#include "caustica/io/exr_layers.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <vector>

#include "caustica/util/error.h"

namespace caustica {

void writeExrLayers(const std::string& path, const Image& image, const AovImage& aovs,
                    const ImageMetadata& metadata) {
    const size_t C = aovs.channels.size();
    if (aovs.width != image.width || aovs.height != image.height ||
        aovs.values.size() != image.pixelCount() * C)
        throw Error(path, 0, "the AOVs' size does not match the image's");
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        for (const std::string& c : aovs.channels)
            header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        header.insert(kAovsAttribute, Imf::StringAttribute(aovs.spec.text()));
        for (const auto& [key, value] : metadata.entries) {
            // A key OpenEXR already set or reserves (type, name, view, ...) would change the file's
            // meaning.
            if (key.empty() || header.find(key) != header.end() || key == "type" || key == "name" ||
                key == "view" || key == "multiView" || key == "tiles" || key == "chunkCount")
                throw Error(path, 0,
                            "metadata key '" + key + "' is empty or a reserved EXR attribute");
            header.insert(key, Imf::StringAttribute(value));
        }
        Imf::OutputFile file(path.c_str(), header);
        Imf::FrameBuffer fb;
        const size_t xs = 3 * sizeof(float), ys = xs * size_t(image.width);
        char* rgb = const_cast<char*>(reinterpret_cast<const char*>(image.rgb.data()));
        fb.insert("R", Imf::Slice(Imf::FLOAT, rgb + 0, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, rgb + 4, xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, rgb + 8, xs, ys));
        char* values = const_cast<char*>(reinterpret_cast<const char*>(aovs.values.data()));
        for (size_t c = 0; c < C; ++c)
            fb.insert(aovs.channels[c],
                      Imf::Slice(Imf::FLOAT, values + c * sizeof(float), C * sizeof(float),
                                 C * sizeof(float) * size_t(image.width)));
        file.setFrameBuffer(fb);
        file.writePixels(image.height);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path, 0, e.what());
    }
}

ExrLayers readExrLayers(const std::string& path) {
    ExrLayers out;
    out.image = readImage(path);  // checks the header and chunks before OpenEXR allocates
    out.metadata = readImageMetadata(path);
    const auto list = out.metadata.entries.find(kAovsAttribute);
    if (list == out.metadata.entries.end()) return out;
    AovImage& aovs = out.aovs;
    aovs.spec = parseAovSpec(list->second, path + ": attribute " + kAovsAttribute);
    aovs.channels = aovs.spec.channelNames();
    aovs.width = out.image.width;
    aovs.height = out.image.height;
    const size_t C = aovs.channels.size();
    aovs.values.assign(out.image.pixelCount() * C, 0.0f);
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(aovs.values.data());
        for (size_t c = 0; c < C; ++c) {
            if (!file.header().channels().findChannel(aovs.channels[c]))
                throw Error(path, 0,
                            "no channel '" + aovs.channels[c] + "' although " + kAovsAttribute +
                                " names it");
            fb.insert(aovs.channels[c],
                      Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), dw, C * sizeof(float),
                                       C * sizeof(float) * size_t(aovs.width)));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path, 0, e.what());
    }
    return out;
}

}  // namespace caustica
