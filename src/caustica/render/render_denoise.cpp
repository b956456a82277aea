// render_denoise.cpp — `caustica render --denoise` (render_denoise.h).
#include "caustica/render/render_denoise.h"

#include <filesystem>

#include "caustica/film/oidn_denoiser.h"
#include "caustica/film/tonemap.h"
#include "caustica/io/exr_feature_layers.h"
#include "caustica/render/render_outputs.h"
#include "caustica/render/renderer.h"
#include "caustica/util/error.h"

namespace caustica {

AovSpec withDenoiseGuides(AovSpec spec, bool withVariance) {
    const auto add = [&](AovType type, const char* name) {
        if (!spec.has(type)) spec.layers.push_back(AovLayer{name, type});
    };
    add(AovType::Albedo, "denoise.albedo");
    if (!spec.has(AovType::GeoNormal)) add(AovType::ShNormal, "denoise.normal");
    add(AovType::Depth, "denoise.depth");
    if (withVariance) add(AovType::Variance, "denoise.variance");
    if (int(spec.layers.size()) > kMaxAovLayers)
        throw Error("--denoise: the AOV list and the denoiser's guides make more than " +
                    std::to_string(kMaxAovLayers) + " layers");
    return spec;
}

std::string denoisedOutputPath(const std::string& path) {
    const std::filesystem::path p(path);
    std::filesystem::path out = p.parent_path() / p.stem();
    return out.string() + ".denoised" + p.extension().string();
}

namespace {

/// The denoised outputs' own stereo settings: the render's, without an anaglyph.
StereoOutputs denoisedStereo(const StereoOutputs& stereo) { return StereoOutputs{stereo.enabled, stereo.separate, ""}; }

Image denoiseRender(const Image& image, const Renderer& renderer, const DenoiseSettings& settings) {
    const AovImage aovs = renderer.developAovs();
    if (renderer.scene().film.eyeWidth == 0) return denoise(image, featuresFromAovs(aovs), settings);
    Image eyes[2];
    for (int eye = 0; eye < 2; ++eye)
        eyes[eye] = denoise(stereoEyeImage(image, eye), featuresFromAovs(stereoEyeAovs(aovs, eye)), settings);
    return sideBySideImage(eyes[0], eyes[1]);
}

}  // namespace

void checkDenoiseOutputs(const std::vector<std::string>& outputs, const DenoiseSettings& settings,
                         const StereoOutputs& stereo) {
    std::vector<std::string> denoised;
    for (const std::string& out : outputs) denoised.push_back(denoisedOutputPath(out));
    for (const std::string& file : stereoOutputFiles(denoised, denoisedStereo(stereo))) checkImageOutputPath(file);
    if (settings.method == DenoiseMethod::Oidn && findOidnLibrary(settings.oidn.library).empty())
        throw Error(kOidnNotFound);
}

std::vector<std::string> writeDenoisedImages(const std::vector<std::string>& outputs, const Image& image,
                                             const Renderer& renderer, const DenoiseSettings& settings,
                                             const StereoOutputs& stereo) {
    const Image denoised = denoiseRender(image, renderer, settings);
    ImageMetadata meta = renderImageMetadata(renderer);
    meta.entries["caustica.denoiser"] = denoiseMethodName(settings.method);
    const ToneMapDesc& tonemap = renderer.scene().film.tonemap;
    Image ldr;  // an ldrfilm's PNGs are tone-mapped, as writeRenderImages writes them
    std::vector<std::string> written;
    for (const std::string& out : outputs) {
        const std::string path = denoisedOutputPath(out);
        const std::string ext = std::filesystem::path(path).extension().string();
        if (stereo.enabled && (ext == ".exr" || ext == ".EXR")) {
            writeStereoExr(path, denoised, meta, stereo.separate);
            for (std::string& file : stereoOutputFiles({path}, denoisedStereo(stereo))) written.push_back(std::move(file));
            continue;
        }
        const bool toneMapped = tonemap.ldr && (ext == ".png" || ext == ".PNG");
        if (toneMapped && ldr.empty()) ldr = displayToPngLinear(toneMap(denoised, tonemap));
        writeImageThroughTemporary(path,
                                   [&](const std::string& tmp) { writeImage(tmp, toneMapped ? ldr : denoised, meta); });
        written.push_back(path);
    }
    return written;
}

}  // namespace caustica
