#include "caustica/integrators/mlt/mlt_loop.h"

#include <chrono>
#include <cmath>

#include "caustica/util/error.h"

namespace caustica {

RenderStats runMlt(MltRenderer& mlt, const MltBudget& budget, const MltIterationFn& iterationDone) {
    if (budget.mutationsPerPixel <= 0 && budget.timeLimit <= 0)
        throw Error("an MLT render needs a budget: mutations per pixel (--spp) or a time limit (--time)");
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    RenderStats stats;
    if (!mlt.started()) mlt.bootstrap();  // a renderer loaded from a checkpoint goes on where it was
    for (;;) {
        mlt.iterate();
        const MltStats& s = mlt.stats();
        stats.seconds = elapsed();
        stats.samples = s.proposals;
        stats.rays = s.rays;
        stats.samplesPerPixel = int(std::lround(mlt.mutationsPerPixel()));
        if (iterationDone) iterationDone(mlt, stats);
        if (budget.cancel && budget.cancel->load()) {
            stats.cancelled = true;
            break;
        }
        if (budget.mutationsPerPixel > 0 && mlt.mutationsPerPixel() >= budget.mutationsPerPixel) break;
        if (budget.timeLimit > 0 && stats.seconds >= budget.timeLimit) break;
    }
    return stats;
}

}  // namespace caustica
