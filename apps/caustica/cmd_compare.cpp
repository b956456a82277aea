// caustica compare A B — error metrics of image A against reference B.
#include <cmath>
#include <cstdio>
#include <string>

#include "commands.h"
#include "caustica/film/image_compare.h"
#include "caustica/io/image_io.h"
#include "caustica/util/error.h"

namespace caustica::cli {

namespace {
/// readImage, refusing an image with NaN or infinite values: its metrics would mean nothing.
Image readComparable(const std::string& path) {
    Image image = readImage(path);
    if (const NonFiniteCount bad = countNonFinite(image); bad.values > 0)
        throw Error(path, 0,
                    std::to_string(bad.pixels) + " of " + std::to_string(image.pixelCount()) +
                        " pixels are not finite (" + std::to_string(bad.values) +
                        " NaN or infinite values): cannot compare");
    return image;
}

/// A JSON number; null for NaN and infinities, which JSON cannot hold.
std::string jsonNumber(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}
}  // namespace

std::function<int()> addCompareCommand(CLI::App& app) {
    struct Options {
        std::string test, reference, errorImage, referenceVariance;
        bool json = false;
    };
    auto opt = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("compare", "Compare an image with a reference: MSE, RMSE, relMSE, MAE");
    cmd->add_option("image", opt->test, "Image to evaluate (.exr, .pfm, .png)")->required();
    cmd->add_option("reference", opt->reference, "Reference image (.exr, .pfm, .png)")->required();
    cmd->add_option("--error-image,-e", opt->errorImage,
                    "Write a false-colour image of the per-pixel relative squared error");
    cmd->add_option("--ref-var", opt->referenceVariance,
                    "Per-pixel variance of the reference's mean (REF.var.exr): also report the errors "
                    "with the reference's own noise removed");
    cmd->add_flag("--json", opt->json, "Print the metrics as one JSON object");
    return [opt] {
        const Image a = readComparable(opt->test), b = readComparable(opt->reference);
        const bool withVar = !opt->referenceVariance.empty();
        const ErrorMetrics m =
            withVar ? compareImages(a, b, readComparable(opt->referenceVariance)) : compareImages(a, b);
        if (opt->json) {
            std::printf("{\"mse\": %s, \"rmse\": %s, \"relmse\": %s, \"mae\": %s, \"pixels\": %zu, "
                        "\"relmse_worst_1pct_share\": %s, \"mean_ratio\": %s",
                        jsonNumber(m.mse).c_str(), jsonNumber(m.rmse).c_str(), jsonNumber(m.relMse).c_str(),
                        jsonNumber(m.mae).c_str(), m.pixels, jsonNumber(m.relMseWorstShare).c_str(),
                        jsonNumber(m.meanRatio).c_str());
            if (withVar)
                std::printf(", \"mse_ref_noise_removed\": %s, \"relmse_ref_noise_removed\": %s",
                            jsonNumber(m.mseRefNoiseRemoved).c_str(), jsonNumber(m.relMseRefNoiseRemoved).c_str());
            std::printf("}\n");
        } else {
            std::printf("MSE     %.6g\nRMSE    %.6g\nrelMSE  %.6g\nMAE     %.6g\npixels  %zu\n"
                        "relMSE share of the worst 1%% of pixels  %.3g\nmean / reference mean  %.4g\n",
                        m.mse, m.rmse, m.relMse, m.mae, m.pixels, m.relMseWorstShare, m.meanRatio);
            if (withVar)
                std::printf("MSE    (reference noise removed) %.6g\nrelMSE (reference noise removed) %.6g\n",
                            m.mseRefNoiseRemoved, m.relMseRefNoiseRemoved);
        }
        if (!opt->errorImage.empty()) writeImage(opt->errorImage, falseColourError(a, b));
        return 0;
    };
}

}  // namespace caustica::cli
