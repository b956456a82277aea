#include "caustica/render/stereo_outputs.h"

#include <algorithm>
#include <filesystem>

#include "caustica/io/exr_layers.h"
#include "caustica/io/exr_multiview.h"
#include "caustica/io/image_io.h"
#include "caustica/render/render_outputs.h"
#include "caustica/util/error.h"

namespace caustica {

namespace fs = std::filesystem;

std::string stereoEyePath(const std::string& exrPath, int eye) {
    fs::path p(exrPath);
    const std::string ext = p.extension().string();
    p.replace_extension();
    return p.string() + (eye == 0 ? ".left" : ".right") + ext;
}

std::vector<std::string> stereoOutputFiles(const std::vector<std::string>& outputs, const StereoOutputs& s) {
    std::vector<std::string> files;
    for (const std::string& out : outputs) {
        if (s.enabled && s.separate && isExrPath(out)) {
            files.push_back(stereoEyePath(out, 0));
            files.push_back(stereoEyePath(out, 1));
        } else {
            files.push_back(out);
        }
    }
    if (s.enabled && !s.anaglyph.empty()) files.push_back(s.anaglyph);
    return files;
}

Image stereoEyeImage(const Image& sideBySide, int eye) {
    if (sideBySide.width % 2 != 0) throw Error("a side-by-side stereo image needs an even width");
    const int w = sideBySide.width / 2;
    Image out(w, sideBySide.height);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) out.pixel(x, y)[c] = sideBySide.pixel(x + eye * w, y)[c];
    return out;
}

AovImage stereoEyeAovs(const AovImage& sideBySide, int eye) {
    if (sideBySide.width % 2 != 0) throw Error("side-by-side stereo AOVs need an even width");
    AovImage out;
    out.width = sideBySide.width / 2;
    out.height = sideBySide.height;
    out.spec = sideBySide.spec;
    out.channels = sideBySide.channels;
    const size_t C = out.channels.size(), row = size_t(out.width) * C;
    out.values.resize(size_t(out.height) * row);
    for (int y = 0; y < out.height; ++y) {
        const float* src = sideBySide.values.data() + (size_t(y) * 2 + size_t(eye)) * row;
        std::copy(src, src + row, out.values.begin() + ptrdiff_t(size_t(y) * row));
    }
    return out;
}

Image sideBySideImage(const Image& left, const Image& right) {
    if (!left.sameSize(right)) throw Error("the two eyes' images differ in size");
    Image out(2 * left.width, left.height);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < left.width; ++x)
            for (int c = 0; c < 3; ++c) {
                out.pixel(x, y)[c] = left.pixel(x, y)[c];
                out.pixel(x + left.width, y)[c] = right.pixel(x, y)[c];
            }
    return out;
}

Image anaglyphImage(const Image& sideBySide) {
    const Image left = stereoEyeImage(sideBySide, 0), right = stereoEyeImage(sideBySide, 1);
    Image out(left.width, left.height);
    for (size_t i = 0; i < out.pixelCount(); ++i) {
        out.rgb[3 * i + 0] = left.rgb[3 * i + 0];
        out.rgb[3 * i + 1] = right.rgb[3 * i + 1];
        out.rgb[3 * i + 2] = right.rgb[3 * i + 2];
    }
    return out;
}

void checkStereoOutputFiles(const std::vector<std::string>& outputs, const StereoOutputs& s) {
    if (s.enabled && !s.anaglyph.empty() && fs::path(s.anaglyph).extension() != ".png")
        throw Error(s.anaglyph + ": the anaglyph is written as a PNG (name it NAME.png)");
    for (const std::string& file : stereoOutputFiles(outputs, s)) checkImageOutputPath(file);
}

void writeAnaglyphPng(const std::string& path, const Image& sideBySide, const ImageMetadata& meta) {
    const Image anaglyph = anaglyphImage(sideBySide);
    writeImageThroughTemporary(path, [&](const std::string& tmp) { writeImage(tmp, anaglyph, meta); });
}

void writeStereoExr(const std::string& path, const Image& sideBySide, const ImageMetadata& meta, bool separate,
                    const AovImage& sideBySideAovs) {
    const Image eyes[2] = {stereoEyeImage(sideBySide, 0), stereoEyeImage(sideBySide, 1)};
    AovImage eyeAovs[2];
    if (!sideBySideAovs.empty())
        for (int eye = 0; eye < 2; ++eye) eyeAovs[eye] = stereoEyeAovs(sideBySideAovs, eye);
    if (!separate) {
        writeImageThroughTemporary(path, [&](const std::string& tmp) {
            writeMultiViewExr(tmp, eyes[0], eyes[1], meta, eyeAovs[0], eyeAovs[1]);
        });
        return;
    }
    for (int eye = 0; eye < 2; ++eye) {
        ImageMetadata eyeMeta = meta;
        eyeMeta.entries["caustica.eye"] = eye == 0 ? "left" : "right";
        writeImageThroughTemporary(stereoEyePath(path, eye), [&](const std::string& tmp) {
            if (eyeAovs[eye].empty())
                writeImage(tmp, eyes[eye], eyeMeta);
            else
                writeExrLayers(tmp, eyes[eye], eyeAovs[eye], eyeMeta);
        });
    }
}

}  // namespace caustica
