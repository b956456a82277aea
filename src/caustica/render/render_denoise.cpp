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

AovSpec withDenoiseGuides(AovSpec spec, bool pixelPasses) {
    const auto add = [&](AovType type, const char* name) {
        if (!spec.has(type)) spec.layers.push_back(AovLayer{name, type});
    };
    add(AovType::Albedo, "denoise.albedo");
    if (!spec.has(AovType::GeoNormal)) add(AovType::ShNormal, "denoise.normal");
    add(AovType::Depth, "denoise.depth");
    if (pixelPasses) add(AovType::Variance, "denoise.variance");
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

void checkDenoiseOutputs(const std::vector<std::string>& outputs, const DenoiseSettings& settings) {
    for (const std::string& out : outputs) checkImageOutputPath(denoisedOutputPath(out));
    if (settings.method == DenoiseMethod::Oidn && findOidnLibrary(settings.oidn.library).empty())
        throw Error(kOidnNotFound);
}

std::vector<std::string> writeDenoisedImages(const std::vector<std::string>& outputs, const Image& image,
                                             const Renderer& renderer, const DenoiseSettings& settings) {
    const Image denoised = denoise(image, featuresFromAovs(renderer.developAovs()), settings);
    ImageMetadata meta = renderImageMetadata(renderer);
    meta.entries["caustica.denoiser"] = denoiseMethodName(settings.method);
    const ToneMapDesc& tonemap = renderer.scene().film.tonemap;
    Image ldr;  // an ldrfilm's PNGs are tone-mapped, as writeRenderImages writes them
    std::vector<std::string> written;
    for (const std::string& out : outputs) {
        const std::string path = denoisedOutputPath(out);
        const std::string ext = std::filesystem::path(path).extension().string();
        const bool toneMapped = tonemap.ldr && (ext == ".png" || ext == ".PNG");
        if (toneMapped && ldr.empty()) ldr = displayToPngLinear(toneMap(denoised, tonemap));
        writeImageThroughTemporary(path,
                                   [&](const std::string& tmp) { writeImage(tmp, toneMapped ? ldr : denoised, meta); });
        written.push_back(path);
    }
    return written;
}

}  // namespace caustica
