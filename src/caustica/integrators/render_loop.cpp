#include "caustica/integrators/render_loop.h"

#include <algorithm>
#include <chrono>

namespace caustica {

RenderStats runRenderLoop(Film& film, const RenderBudget& budget, const RenderPassFn& renderPass,
                          const PassDoneFn& passDone) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

    auto filmSpp = [&] { return int(film.samplesPerPixel()); };
    RenderStats stats;
    stats.samplesPerPixel = filmSpp();
    SamplePass pass(film.width(), film.height(), std::max(1, budget.samplesPerPass));
    const uint64_t pixels = uint64_t(film.width()) * uint64_t(film.height());
    double lastPassSeconds = 0;

    for (;;) {
        const int done = filmSpp();
        if (budget.samplesPerPixel > 0 && done >= budget.samplesPerPixel) break;
        if (budget.cancel && budget.cancel->load()) {
            stats.cancelled = true;
            break;
        }
        if (budget.timeLimit > 0) {
            // Stop when the next pass would most likely overrun the budget by more than half a pass.
            double t = elapsed();
            if (t >= budget.timeLimit || (stats.samples > 0 && t + 0.5 * lastPassSeconds > budget.timeLimit)) break;
        }
        int k = std::max(1, budget.samplesPerPass);
        if (budget.samplesPerPixel > 0) k = std::min(k, budget.samplesPerPixel - done);
        if (k != pass.samplesPerPixel) pass = SamplePass(film.width(), film.height(), k);

        const double passStart = elapsed();
        stats.rays += renderPass(done, k, pass);
        film.addPass(pass);
        lastPassSeconds = elapsed() - passStart;

        stats.samples += pixels * uint64_t(k);
        stats.samplesPerPixel = filmSpp();
        stats.invalidSamples = film.invalidSamples();
        stats.seconds = elapsed();
        if (passDone) passDone(film, stats);
    }
    stats.seconds = elapsed();
    stats.samplesPerPixel = filmSpp();
    stats.invalidSamples = film.invalidSamples();
    return stats;
}

}  // namespace caustica
