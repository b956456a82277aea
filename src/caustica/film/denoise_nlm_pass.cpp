// denoise_nlm_pass.cpp — the NL-means denoiser's driver for the device this file is compiled for
// (launch.h: g++ makes the CPU's; cuda/denoise_driver.cu includes this file for nvcc).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "caustica/film/denoise_nlm_pass.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

/// A guide's values on the host, ready for upload: non-finite values 0; depth (one channel)
/// divided by its largest finite magnitude, so that tau means the same for any scene scale.
std::vector<float> featureValues(const Image& image, int channels) {
    const size_t n = image.pixelCount();
    std::vector<float> out(n * size_t(channels));
    float scale = 1.0f;
    if (channels == 1) {
        float largest = 0.0f;
        for (size_t i = 0; i < n; ++i)
            if (std::isfinite(image.rgb[3 * i])) largest = std::fmax(largest, std::fabs(image.rgb[3 * i]));
        if (largest > 0.0f) scale = 1.0f / largest;
    }
    for (size_t i = 0; i < n; ++i)
        for (int ch = 0; ch < channels; ++ch) {
            const float v = image.rgb[3 * i + size_t(ch)];
            out[i * size_t(channels) + size_t(ch)] = std::isfinite(v) ? v * scale : 0.0f;
        }
    return out;
}

void checkGuideSize(const Image& color, const std::optional<Image>& guide, const char* name) {
    if (guide && !guide->sameSize(color))
        throw Error(std::string("denoise: the ") + name + " image is " + std::to_string(guide->width) + " x " +
                    std::to_string(guide->height) + ", the colour " + std::to_string(color.width) + " x " +
                    std::to_string(color.height));
}

template <class Exec>
void launchPrepare(Exec exec, size_t n, const float* input, float* color, uint8_t* valid) {
    launch(exec, "denoise_nlm_prepare", n,
           [=] CA_HD(size_t i) { nlmPrepareColor(input, color, valid, i); });
}

template <class Exec>
void launchVarianceEstimate(Exec exec, size_t n, NlmView view, float* variance) {
    launch(exec, "denoise_nlm_variance", n,
           [=] CA_HD(size_t i) { nlmEstimateVariance(view, variance, i); });
}

template <class Exec>
void launchVarianceSmooth(Exec exec, size_t n, NlmView view, const float* given, float* variance) {
    launch(exec, "denoise_nlm_variance_smooth", n,
           [=] CA_HD(size_t i) { nlmSmoothVariance(view, given, variance, i); });
}

template <class Exec>
void launchFilter(Exec exec, size_t n, NlmView view, float* out) {
    launch(exec, "denoise_nlm_filter", n, [=] CA_HD(size_t i) { nlmFilterPixel(view, out, i); }, 16);
}

}  // namespace

template <>
Image denoiseNlm<DriverExec>(DriverExec exec, const Image& color, const DenoiseFeatures& features,
                             const NlmParams& params) {
    checkGuideSize(color, features.albedo, "albedo");
    checkGuideSize(color, features.normal, "normal");
    checkGuideSize(color, features.depth, "depth");
    checkGuideSize(color, features.variance, "variance");
    if (params.radius < 0 || params.patchRadius < 0 || !(params.kColor > 0) || !(params.kFeature > 0) ||
        !(params.tau > 0) || !(params.alpha >= 0))
        throw Error("denoise: NL-means parameters out of range (radius, patch radius >= 0; k_c, k_f, tau > 0; "
                    "alpha >= 0)");
    const size_t n = color.pixelCount();
    Image result(color.width, color.height);
    if (n == 0) return result;
    const Device device = DriverExec::device();

    Buffer<float> input(device, color.rgb);
    Buffer<float> clean(device, 3 * n), out(device, 3 * n);
    Buffer<uint8_t> valid(device, n);
    launchPrepare(exec, n, input.data(), clean.data(), valid.data());

    NlmView view;
    view.width = color.width;
    view.height = color.height;
    view.color = clean.data();
    view.valid = valid.data();
    view.params = params;

    // Guides in a fixed order: albedo, normal, depth.
    std::vector<Buffer<float>> guides;
    guides.reserve(kMaxNlmFeatures);
    const std::pair<const std::optional<Image>*, int> wanted[kMaxNlmFeatures] = {
        {&features.albedo, 3}, {&features.normal, 3}, {&features.depth, 1}};
    for (const auto& [image, channels] : wanted) {
        if (!*image) continue;
        guides.emplace_back(device, featureValues(**image, channels));
        view.features[view.featureCount++] = NlmFeature{guides.back().data(), channels};
    }

    // Kept alive until the filter has run (GPU launches are asynchronous).
    Buffer<float> variance(device, 3 * n), given;
    if (features.variance) {
        given = Buffer<float>(device, features.variance->rgb);
        launchVarianceSmooth(exec, n, view, given.data(), variance.data());
    } else {
        launchVarianceEstimate(exec, n, view, variance.data());
    }
    view.variance = variance.data();

    launchFilter(exec, n, view, out.data());
    out.copyToHost(Span<float>(result.rgb.data(), result.rgb.size()));
    return result;
}

}  // namespace caustica
