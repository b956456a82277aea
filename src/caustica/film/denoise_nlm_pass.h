// denoise_nlm_pass.h — the feature-guided NL-means denoiser's driver for one device
// (denoise_nlm.h holds the formulas). Single-source: denoise_nlm_pass.cpp defines it for the
// device its compiler builds (g++: CpuExec; nvcc: GpuExec through cuda/denoise_driver.cu);
// render/denoise.h picks one at run time with onDevice.
#pragma once

#include "caustica/film/denoise_features.h"
#include "caustica/film/denoise_nlm.h"
#include "caustica/film/image.h"

namespace caustica {

/// Filters `color` with the guides in `features` (each the colour's size, else caustica::Error)
/// on Exec's device. Non-finite colour values never reach the output (denoise_nlm.h).
template <class Exec>
Image denoiseNlm(Exec exec, const Image& color, const DenoiseFeatures& features, const NlmParams& params);

}  // namespace caustica
