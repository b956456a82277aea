// render_options.h — the options of `caustica render`, parsed into the library's RenderRequest
// and RunControl (render/), and the validators that refuse NaN, infinities and out-of-range
// numbers with readable bounds.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "caustica/render/render_request.h"
#include "caustica/render/render_run.h"

namespace caustica::cli {

struct RenderOptions {
    std::string scene;
    std::vector<std::string> defines;
    std::string res;  // WIDTHxHEIGHT
    std::string accel = "embree";
    std::string embreeIsa = "auto";
    int threads = 0;
    uint64_t seed = 0;  // request.seed when --seed is given
    /// The integrators' options (integrator_registry.h), by flag: parameter name and value.
    std::map<std::string, std::pair<std::string, std::string>> integratorOptions;
    bool kernelStats = false;
    std::string stereo, stereoOutput = "multiview";  // --stereo MODE, --stereo-output
    double interocular = 0.065, convergence = 1.95;
    std::string denoise, oidnLibrary;  // --denoise METHOD, --oidn-library PATH
    RenderRequest request;
    RunControl control;
};

/// Registers every option of `render` on `cmd`, writing into `options`.
void addRenderOptions(CLI::App& cmd, RenderOptions& options);
/// Fills what the parsed strings mean into options.request (resolution, accel, defines, seed).
void resolveRenderOptions(RenderOptions& options, const CLI::App& cmd);

/// A number in [lo, hi] that is finite; the message prints the bounds as written here.
CLI::Validator finiteRange(double lo, double hi, const std::string& bounds);

}  // namespace caustica::cli
