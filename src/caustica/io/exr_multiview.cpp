#include "caustica/io/exr_multiview.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiView.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <exception>

#include "caustica/io/exr_layers.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

const char* const kViews[2] = {"left", "right"};
const char* const kChannels[3] = {"R", "G", "B"};

/// Slices for an image's R, G, B (interleaved rgb) under `names`, placed for data window `dw`.
void insertImageSlices(Imf::FrameBuffer& fb, Image& image, const std::string (&names)[3], const Imath::Box2i& dw) {
    const size_t xs = 3 * sizeof(float), ys = xs * size_t(image.width);
    char* base = reinterpret_cast<char*>(image.rgb.data());
    for (int c = 0; c < 3; ++c) fb.insert(names[c], Imf::Slice::Make(Imf::FLOAT, base + 4 * c, dw, xs, ys));
}

/// Slices for every AOV channel of `aovs` (interleaved values) in view `view`.
void insertAovSlices(Imf::FrameBuffer& fb, AovImage& aovs, int view, const Imath::Box2i& dw) {
    const size_t C = aovs.channels.size(), xs = C * sizeof(float), ys = xs * size_t(aovs.width);
    char* base = reinterpret_cast<char*>(aovs.values.data());
    for (size_t c = 0; c < C; ++c)
        fb.insert(multiViewChannelName(aovs.channels[c], view),
                  Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), dw, xs, ys));
}

bool sameAovs(const AovImage& a, const AovImage& b, const Image& image) {
    const size_t C = a.channels.size();
    return a.spec.text() == b.spec.text() && a.channels == b.channels && a.width == image.width &&
           a.height == image.height && b.width == image.width && b.height == image.height &&
           a.values.size() == image.pixelCount() * C && b.values.size() == a.values.size();
}

}  // namespace

std::string multiViewChannelName(const std::string& channel, int view) {
    const size_t dot = channel.rfind('.');
    if (dot == std::string::npos) return view == 0 ? channel : std::string(kViews[view]) + "." + channel;
    return channel.substr(0, dot) + "." + kViews[view] + channel.substr(dot);
}

void writeMultiViewExr(const std::string& path, const Image& left, const Image& right, const ImageMetadata& meta,
                       const AovImage& leftAovs, const AovImage& rightAovs) {
    if (!left.sameSize(right) || left.empty()) throw Error(path + ": the two views differ in size or are empty");
    const bool aovs = !leftAovs.empty() || !rightAovs.empty();
    if (aovs && !sameAovs(leftAovs, rightAovs, left))
        throw Error(path + ": the two views' AOVs differ in their list or size, or not the image's size");
    try {
        Imf::Header header(left.width, left.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::addMultiView(header, Imf::StringVector{kViews[0], kViews[1]});
        for (int view = 0; view < 2; ++view) {
            for (const char* c : kChannels)
                header.channels().insert(multiViewChannelName(c, view), Imf::Channel(Imf::FLOAT));
            if (aovs)
                for (const std::string& c : leftAovs.channels)
                    header.channels().insert(multiViewChannelName(c, view), Imf::Channel(Imf::FLOAT));
        }
        if (aovs) header.insert(kAovsAttribute, Imf::StringAttribute(leftAovs.spec.text()));
        for (const auto& [key, value] : meta.entries) {
            if (key.empty() || header.find(key) != header.end() || key == "view")
                throw Error(path + ": metadata key '" + key + "' is empty or a reserved EXR attribute");
            header.insert(key, Imf::StringAttribute(value));
        }
        Imf::OutputFile file(path.c_str(), header);
        Imf::FrameBuffer fb;
        const Imath::Box2i& dw = header.dataWindow();
        // The slices only read: the writer's inputs are const, OpenEXR's slices are not.
        Image* images[2] = {const_cast<Image*>(&left), const_cast<Image*>(&right)};
        AovImage* layers[2] = {const_cast<AovImage*>(&leftAovs), const_cast<AovImage*>(&rightAovs)};
        for (int view = 0; view < 2; ++view) {
            std::string names[3];
            for (int c = 0; c < 3; ++c) names[c] = multiViewChannelName(kChannels[c], view);
            insertImageSlices(fb, *images[view], names, dw);
            if (aovs) insertAovSlices(fb, *layers[view], view, dw);
        }
        file.setFrameBuffer(fb);
        file.writePixels(left.height);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot write the multi-view EXR (" + e.what() + ")");
    }
}

std::vector<std::string> exrViews(const std::string& path) {
    checkExrFile(path);
    try {
        Imf::InputFile file(path.c_str());
        if (!Imf::hasMultiView(file.header())) return {};
        const Imf::StringVector views = Imf::multiView(file.header());
        return std::vector<std::string>(views.begin(), views.end());
    } catch (const std::exception& e) {
        throw Error(path + ": cannot read the EXR header (" + e.what() + ")");
    }
}

StereoImagePair readMultiViewExr(const std::string& path) {
    checkExrFile(path);  // header, window and chunks sane before OpenEXR allocates
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        if (!Imf::hasMultiView(header)) throw Error(path + ": not a multi-view EXR (no multiView attribute)");
        const Imf::StringVector views = Imf::multiView(header);
        if (views.size() != 2 || views[0] != kViews[0] || views[1] != kViews[1])
            throw Error(path + ": expected the views left and right in its multiView attribute");
        AovSpec spec;
        const auto* list = header.findTypedAttribute<Imf::StringAttribute>(kAovsAttribute);
        if (list) spec = parseAovSpec(list->value(), path + ": attribute " + kAovsAttribute);
        const std::vector<std::string> aovChannels = spec.channelNames();
        const Imf::ChannelList& channels = header.channels();
        std::string names[2][3];
        for (int view = 0; view < 2; ++view) {
            for (int c = 0; c < 3; ++c) {
                // The default (first) view's channels may be unprefixed; every view's may be "VIEW.C".
                const std::string prefixed = std::string(kViews[view]) + "." + kChannels[c];
                names[view][c] = view == 0 && channels.findChannel(kChannels[c]) ? kChannels[c] : prefixed;
                if (!channels.findChannel(names[view][c]))
                    throw Error(path + ": view '" + kViews[view] + "' has no channel " + kChannels[c]);
            }
            for (const std::string& c : aovChannels)
                if (!channels.findChannel(multiViewChannelName(c, view)))
                    throw Error(path + ": no channel '" + multiViewChannelName(c, view) + "' although " +
                                kAovsAttribute + " names it");
        }
        // Allocated only now: the window passed checkExrFile's size check.
        const Imath::Box2i dw = header.dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        StereoImagePair pair{Image(w, h), Image(w, h), {}, {}};
        Imf::FrameBuffer fb;
        for (int view = 0; view < 2; ++view) {
            insertImageSlices(fb, view == 0 ? pair.left : pair.right, names[view], dw);
            if (aovChannels.empty()) continue;
            AovImage& aovs = view == 0 ? pair.leftAovs : pair.rightAovs;
            aovs.width = w;
            aovs.height = h;
            aovs.spec = spec;
            aovs.channels = aovChannels;
            aovs.values.assign(size_t(w) * size_t(h) * aovChannels.size(), 0.0f);
            insertAovSlices(fb, aovs, view, dw);
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        return pair;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot read the multi-view EXR (" + e.what() + ")");
    }
}

}  // namespace caustica
