// denoise_file.cpp — `caustica denoise` of a single-view or multi-view file (denoise_file.h).
#include "caustica/render/denoise_file.h"

#include <filesystem>

#include "caustica/io/exr_feature_layers.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/exr_multiview.h"
#include "caustica/io/image_io.h"
#include "caustica/render/render_outputs.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

/// Refuses an output that is the input itself (the noisy image is always kept).
void checkNotInput(const std::string& input, const std::string& output) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const bool same = fs::exists(output, ec) ? fs::equivalent(input, output, ec)
                                             : fs::weakly_canonical(input, ec) == fs::weakly_canonical(output, ec);
    if (same) throw Error(output, 0, "the output would overwrite the noisy input: give another -o path");
}

void noteGuides(DenoiseFileResult& r, const DenoiseFeatures& f, bool first) {
    const auto both = [first](bool& seen, bool now) { seen = first ? now : seen && now; };
    both(r.albedo, f.albedo.has_value());
    both(r.normal, f.normal.has_value());
    both(r.depth, f.depth.has_value());
    both(r.variance, f.variance.has_value());
}

ImageMetadata denoisedMetadata(const std::string& input, const DenoiseSettings& settings) {
    ImageMetadata metadata = readImageMetadata(input);
    metadata.entries.erase(kAovsAttribute);  // the output holds the colour only
    metadata.entries["caustica.denoiser"] = denoiseMethodName(settings.method);
    metadata.entries["caustica.denoised_from"] = input;
    return metadata;
}

DenoiseFileResult denoiseStereoPair(const DenoiseFileRequest& request, const DenoiseSettings& settings) {
    const std::string& in = request.input;
    for (const auto& [file, option] : {std::pair{request.albedo, "--albedo"}, {request.normal, "--normal"},
                                       {request.depth, "--depth"}, {request.variance, "--variance"}})
        if (!file.empty())
            throw Error(std::string(option) + ": " + in +
                        " is a multi-view EXR, whose guides are each view's own layers; guide files apply to "
                        "single-view images");
    if (!isExrPath(request.output))
        throw Error(request.output, 0, "a multi-view input is written as a multi-view EXR: give an .exr output");
    const StereoImagePair pair = readMultiViewExr(in);  // refuses views other than left and right
    DenoiseFileResult result{pair.left.width, pair.left.height, 2};
    Image denoised[2];
    for (int view = 0; view < 2; ++view) {
        const DenoiseFeatures features =
            request.ignoreLayers ? DenoiseFeatures{} : featuresFromAovs(view == 0 ? pair.leftAovs : pair.rightAovs);
        noteGuides(result, features, view == 0);
        denoised[view] = denoise(view == 0 ? pair.left : pair.right, features, settings);
    }
    writeMultiViewExr(request.output, denoised[0], denoised[1], denoisedMetadata(in, settings));
    return result;
}

}  // namespace

DenoiseFileResult denoiseFile(const DenoiseFileRequest& request, const DenoiseSettings& settings) {
    checkNotInput(request.input, request.output);
    checkImageOutputPath(request.output);
    if (isExrPath(request.input)) {
        const std::vector<std::string> views = exrViews(request.input);
        if (!views.empty()) return denoiseStereoPair(request, settings);
    }
    const Image color = readImage(request.input);
    DenoiseFeatures features;
    if (!request.ignoreLayers && isExrPath(request.input)) features = readFeatureLayers(request.input);
    if (!request.albedo.empty()) features.albedo = readImage(request.albedo);
    if (!request.normal.empty()) features.normal = readImage(request.normal, ImageReadOptions{.raw = true});
    if (!request.depth.empty()) features.depth = readImage(request.depth);
    if (!request.variance.empty()) features.variance = readImage(request.variance);
    DenoiseFileResult result{color.width, color.height, 1};
    noteGuides(result, features, true);
    writeImage(request.output, denoise(color, features, settings), denoisedMetadata(request.input, settings));
    return result;
}

}  // namespace caustica
