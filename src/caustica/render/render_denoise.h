// render_denoise.h — `caustica render --denoise`: the guide AOVs a render adds for the denoiser,
// and the denoised copies of the outputs written at the end of the render (NAME.denoised.EXT
// beside NAME.EXT, which keeps the noisy image). The denoiser itself is render/denoise.h.
#pragma once

#include <string>
#include <vector>

#include "caustica/film/aov_layers.h"
#include "caustica/render/denoise.h"
#include "caustica/render/stereo_outputs.h"

namespace caustica {

class Renderer;

/// `spec` with the guides the denoisers read added where it has none of their type: albedo,
/// sh_normal, depth, and (when the integrator can make the variance AOV: pixel samples or step
/// estimates) variance, named "denoise.albedo", ... .
AovSpec withDenoiseGuides(AovSpec spec, bool withVariance);

/// Where the denoised copy of output `path` goes: "out/a.exr" -> "out/a.denoised.exr".
std::string denoisedOutputPath(const std::string& path);

/// Refuses, before rendering, what would make the denoising at the end fail: an output the
/// denoised copy (a stereo render's: its eye files) cannot be written to, an OIDN that cannot be
/// found.
void checkDenoiseOutputs(const std::vector<std::string>& outputs, const DenoiseSettings& settings,
                         const StereoOutputs& stereo = {});

/// Denoises the render's image with its guide AOVs and writes it to every output's denoised
/// path (colour only). A stereo render is denoised eye by eye (each with its own guides, so the
/// filter never mixes the eyes) and written as its outputs are (stereo_outputs.h; no anaglyph).
/// Returns the paths written.
std::vector<std::string> writeDenoisedImages(const std::vector<std::string>& outputs, const Image& image,
                                             const Renderer& renderer, const DenoiseSettings& settings,
                                             const StereoOutputs& stereo = {});

}  // namespace caustica
