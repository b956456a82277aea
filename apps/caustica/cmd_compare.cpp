// caustica compare A B — error metrics of image A against reference B.
#include <cstdio>

#include "commands.h"
#include "caustica/film/image_compare.h"
#include "caustica/io/image_io.h"

namespace caustica::cli {

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
        Image a = readImage(opt->test), b = readImage(opt->reference);
        const bool withVar = !opt->referenceVariance.empty();
        const ErrorMetrics m = withVar ? compareImages(a, b, readImage(opt->referenceVariance)) : compareImages(a, b);
        if (opt->json) {
            std::printf("{\"mse\": %.9g, \"rmse\": %.9g, \"relmse\": %.9g, \"mae\": %.9g, \"pixels\": %zu, "
                        "\"relmse_worst_1pct_share\": %.9g",
                        m.mse, m.rmse, m.relMse, m.mae, m.pixels, m.relMseWorstShare);
            if (withVar)
                std::printf(", \"mse_ref_noise_removed\": %.9g, \"relmse_ref_noise_removed\": %.9g",
                            m.mseRefNoiseRemoved, m.relMseRefNoiseRemoved);
            std::printf("}\n");
        } else {
            std::printf("MSE     %.6g\nRMSE    %.6g\nrelMSE  %.6g\nMAE     %.6g\npixels  %zu\n"
                        "relMSE share of the worst 1%% of pixels  %.3g\n",
                        m.mse, m.rmse, m.relMse, m.mae, m.pixels, m.relMseWorstShare);
            if (withVar)
                std::printf("MSE    (reference noise removed) %.6g\nrelMSE (reference noise removed) %.6g\n",
                            m.mseRefNoiseRemoved, m.relMseRefNoiseRemoved);
        }
        if (!opt->errorImage.empty()) writeImage(opt->errorImage, falseColourError(a, b));
        return 0;
    };
}

}  // namespace caustica::cli
