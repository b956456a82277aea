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

#include "caustica/util/error.h"

namespace caustica {
namespace {

const char* const kViews[2] = {"left", "right"};
const char* const kChannels[3] = {"R", "G", "B"};

/// Channel c of view `view` under the multi-view convention: the default (first) view may be
/// unprefixed; every other view is "VIEW.C".
std::string viewChannel(int view, int c) {
    return view == 0 ? std::string(kChannels[c]) : std::string(kViews[view]) + "." + kChannels[c];
}

void insertSlices(Imf::FrameBuffer& fb, const Image& image, int view) {
    const size_t xs = 3 * sizeof(float), ys = xs * size_t(image.width);
    char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
    for (int c = 0; c < 3; ++c)
        fb.insert(viewChannel(view, c), Imf::Slice(Imf::FLOAT, base + 4 * c, xs, ys));
}

}  // namespace

void writeMultiViewExr(const std::string& path, const Image& left, const Image& right, const ImageMetadata& meta) {
    if (!left.sameSize(right) || left.empty()) throw Error(path + ": the two views differ in size or are empty");
    try {
        Imf::Header header(left.width, left.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        Imf::addMultiView(header, Imf::StringVector{kViews[0], kViews[1]});
        for (int view = 0; view < 2; ++view)
            for (int c = 0; c < 3; ++c) header.channels().insert(viewChannel(view, c), Imf::Channel(Imf::FLOAT));
        for (const auto& [key, value] : meta.entries) {
            if (key.empty() || header.find(key) != header.end() || key == "view")
                throw Error(path + ": metadata key '" + key + "' is empty or a reserved EXR attribute");
            header.insert(key, Imf::StringAttribute(value));
        }
        Imf::OutputFile file(path.c_str(), header);
        Imf::FrameBuffer fb;
        insertSlices(fb, left, 0);
        insertSlices(fb, right, 1);
        file.setFrameBuffer(fb);
        file.writePixels(left.height);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot write the multi-view EXR (" + e.what() + ")");
    }
}

StereoImagePair readMultiViewExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        if (!Imf::hasMultiView(header)) throw Error(path + ": not a multi-view EXR (no multiView attribute)");
        const Imf::StringVector views = Imf::multiView(header);
        const Imath::Box2i dw = header.dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        StereoImagePair pair{Image(w, h), Image(w, h)};
        Imf::FrameBuffer fb;
        for (int view = 0; view < 2; ++view) {
            if (views.size() != 2 || views[0] != kViews[0] || views[1] != kViews[1])
                throw Error(path + ": expected the views left and right in its multiView attribute");
            std::string names[3];
            for (int c = 0; c < 3; ++c) {
                // The default (first) view's channels may be unprefixed; every view's may be "VIEW.C".
                const std::string prefixed = std::string(kViews[view]) + "." + kChannels[c];
                names[c] = view == 0 && header.channels().findChannel(kChannels[c]) ? kChannels[c] : prefixed;
                if (!header.channels().findChannel(names[c]))
                    throw Error(path + ": view '" + kViews[view] + "' has no channel " + kChannels[c]);
            }
            Image& image = view == 0 ? pair.left : pair.right;
            const size_t xs = 3 * sizeof(float), ys = xs * size_t(w);
            char* base = reinterpret_cast<char*>(image.rgb.data()) - (size_t(dw.min.x) * xs + size_t(dw.min.y) * ys);
            for (int c = 0; c < 3; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + 4 * c, xs, ys));
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
