// denoise.cpp — the method and device choice of denoise().
#include "caustica/render/denoise.h"

#include "caustica/film/denoise_nlm_pass.h"
#include "caustica/parallel/launch.h"
#include "caustica/util/error.h"

namespace caustica {

DenoiseMethod parseDenoiseMethod(const std::string& name) {
    if (name == "nlm") return DenoiseMethod::Nlm;
    if (name == "oidn") return DenoiseMethod::Oidn;
    throw Error("unknown denoiser '" + name + "' (choose nlm or oidn)");
}

const char* denoiseMethodName(DenoiseMethod method) {
    return method == DenoiseMethod::Oidn ? "oidn" : "nlm";
}

Image denoise(const Image& color, const DenoiseFeatures& features, const DenoiseSettings& settings) {
    if (color.empty()) throw Error("denoise: the colour image is empty");
    if (settings.method == DenoiseMethod::Oidn) return denoiseOidn(color, features, settings.oidn);
    return onDevice(settings.device, [&](auto exec) { return denoiseNlm(exec, color, features, settings.nlm); });
}

}  // namespace caustica
