// render_helpers.h — rendering whole scenes from tests through the library (no CLI).
#pragma once

#include <tbb/task_arena.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/render/renderer.h"
#include "caustica/io/scene_loader.h"

namespace caustica::test {

inline std::string sourcePath(const std::string& relative) {
    return std::string(CAUSTICA_SOURCE_DIR) + "/" + relative;
}

/// The path tracer's settings of a loaded scene's <integrator>.
inline PathSettings scenePathSettings(const Scene& scene) {
    IntegratorParams params(scene.integrator);
    return readPathSettings(params);
}

struct RenderRequest {
    int spp = 16;
    uint64_t seed = 0;
    AccelKind accel = AccelKind::Embree;
    int threads = 0;  // 0 = all
    bool wavefront = false;  // path tracer execution: megakernel (false) or wavefront (true)
};

/// Renders a loaded scene with its integrator through the render session and returns the
/// developed image.
inline Image renderImage(const Scene& scene, const RenderRequest& request) {
    caustica::RenderRequest r;
    r.samplesPerPixel = request.spp;
    r.samplesPerPass = 4;
    r.seed = request.seed;
    r.accel = request.accel;
    r.device = "cpu";
    r.pathMode = request.wavefront ? "wavefront" : "megakernel";
    auto render = [&] {
        Renderer renderer(scene, r);
        while (!renderer.finished()) renderer.step();
        return renderer.develop();
    };
    if (request.threads > 0) {
        tbb::task_arena arena(request.threads);
        return arena.execute(render);
    }
    return render();
}

/// Per-pixel mean and variance of the mean over `runs` independent renders (seeds 1..runs), and
/// each run's image mean (the spread of those gives the variance of the image mean, correlations
/// between pixels from the filter included).
struct RenderEnsemble {
    Image mean, varianceOfMean;
    std::vector<double> runImageMeans;
};

inline RenderEnsemble renderEnsemble(const Scene& scene, int runs, int sppPerRun, AccelKind accel = AccelKind::Embree) {
    RenderEnsemble e;
    std::vector<Image> images;
    for (int i = 0; i < runs; ++i) {
        images.push_back(renderImage(scene, {sppPerRun, uint64_t(1000 + i), accel, 0}));
        double sum = 0;
        for (float v : images.back().rgb) sum += v;
        e.runImageMeans.push_back(sum / double(images.back().rgb.size()));
    }
    e.mean = images[0];
    e.varianceOfMean = images[0];
    for (size_t j = 0; j < e.mean.rgb.size(); ++j) {
        double s = 0, s2 = 0;
        for (const Image& im : images) {
            s += im.rgb[j];
            s2 += double(im.rgb[j]) * im.rgb[j];
        }
        double m = s / runs;
        double var = std::max(0.0, (s2 - runs * m * m) / (runs - 1));
        e.mean.rgb[j] = float(m);
        e.varianceOfMean.rgb[j] = float(var / runs);
    }
    return e;
}

inline double meanOf(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
}

inline double varianceOfMeanOf(const std::vector<double>& v) {
    double m = meanOf(v), s = 0;
    for (double x : v) s += (x - m) * (x - m);
    return s / double(v.size() - 1) / double(v.size());
}

}  // namespace caustica::test
