#include "caustica/render/stereo_outputs.h"

#include <filesystem>

#include "caustica/io/exr_multiview.h"
#include "caustica/render/render_outputs.h"
#include "caustica/util/error.h"

namespace caustica {

namespace fs = std::filesystem;

namespace {
bool isExr(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    return ext == ".exr" || ext == ".EXR";
}

}  // namespace

std::string stereoEyePath(const std::string& exrPath, int eye) {
    fs::path p(exrPath);
    const std::string ext = p.extension().string();
    p.replace_extension();
    return p.string() + (eye == 0 ? ".left" : ".right") + ext;
}

std::vector<std::string> stereoOutputFiles(const std::vector<std::string>& outputs, const StereoOutputs& s) {
    std::vector<std::string> files;
    for (const std::string& out : outputs) {
        if (s.enabled && s.separate && isExr(out)) {
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

void writeStereoExr(const std::string& path, const Image& sideBySide, const ImageMetadata& meta, bool separate) {
    const Image left = stereoEyeImage(sideBySide, 0), right = stereoEyeImage(sideBySide, 1);
    if (!separate) {
        writeImageThroughTemporary(path, [&](const std::string& tmp) { writeMultiViewExr(tmp, left, right, meta); });
        return;
    }
    for (int eye = 0; eye < 2; ++eye) {
        ImageMetadata eyeMeta = meta;
        eyeMeta.entries["caustica.eye"] = eye == 0 ? "left" : "right";
        writeImageThroughTemporary(stereoEyePath(path, eye),
                       [&](const std::string& tmp) { writeImage(tmp, eye == 0 ? left : right, eyeMeta); });
    }
}

}  // namespace caustica
