// denoise.h — denoising a rendered image: the library entry that `caustica denoise` (and, once
// the film has AOVs, `render --denoise`) calls. The noisy image is an input only: callers keep it.
#pragma once

#include <string>

#include "caustica/film/denoise_features.h"
#include "caustica/film/denoise_nlm.h"
#include "caustica/film/image.h"
#include "caustica/film/oidn_denoiser.h"
#include "caustica/parallel/device.h"

namespace caustica {

enum class DenoiseMethod {
    Nlm,   ///< caustica's feature-guided NL-means (film/denoise_nlm.h), always available
    Oidn,  ///< Intel Open Image Denoise, loaded at run time (film/oidn_denoiser.h)
};

/// "nlm" or "oidn"; anything else throws caustica::Error naming the choices.
DenoiseMethod parseDenoiseMethod(const std::string& name);
const char* denoiseMethodName(DenoiseMethod method);

struct DenoiseSettings {
    DenoiseMethod method = DenoiseMethod::Nlm;
    NlmParams nlm;                   ///< NL-means parameters
    OidnOptions oidn;                ///< OIDN library path and threads
    Device device = Device::cpu();   ///< where NL-means runs (OIDN runs on its CPU device)
};

/// The denoised colour. Throws caustica::Error for an empty colour image, guides of another
/// size, bad parameters, or an OIDN that is absent or fails.
Image denoise(const Image& color, const DenoiseFeatures& features, const DenoiseSettings& settings);

}  // namespace caustica
