// spatial_bench.cpp — the photon lookup structures (src/caustica/spatial/) side by side: build
// time, bytes per point and queries per second of every structure for every query type on
// synthetic and real SPPM point sets, on the CPU, written as CSV (plot:
// bench/spatial_bench_plot.py). The point sets, structures, queries, totals check and CSV are
// spatial_bench_core.h's (shared with bench_gpu_spatial.cu, the same on the GPU).
//
//   spatial_bench [--sets uniform,cornell-water,glass-caustic,water-1080p] [--repeat 3]
//                 [--iterations 8] [--photons 262144] [--threads N] [--scale 1]
//                 [--structures NAME,...] [--csv FILE]
//
// Every figure is the best (minimum) of --repeat runs. Queries run in parallel (launch over
// CpuExec, all threads or --threads). Every structure must return exactly the same sets
// (point_set.h), so the result counts and index sums of one set and query must agree between all
// structures; the program says so loudly and exits with status 1 when they do not.
#include <tbb/global_control.h>

#include <cstdio>
#include <exception>
#include <memory>

#include "spatial_bench_core.h"

using namespace caustica;
using namespace caustica::spatial_bench;

int main(int argc, char** argv) {
    const Program program{"spatial_bench", "spatial"};
    const Options o = parseOptions(program, argc, argv);
    std::unique_ptr<tbb::global_control> threadLimit;
    if (o.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    const int threads =
        int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

    try {
        Report report(o.csv.empty() ? todaysCsv(program) : o.csv);
        AgreementCheck agreement;
        Context context{o, threads, report, agreement};
        std::printf("spatial_bench: %d threads, best of %d, scale %g\n", threads, o.repeat,
                    o.scale);
        const auto start = Clock::now();
        forEachSet(o, [&](const BenchSet& s) { measureSet(CpuExec{}, s, context); });
        std::printf("\nwrote %s (%.0f s)\n", report.path().c_str(), msSince(start) * 1e-3);
        if (!agreement.summarize()) return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "spatial_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
