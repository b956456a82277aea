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
#include <cstdio>

#include "spatial_bench_core.h"

using namespace caustica;
using namespace caustica::spatial_bench;

int main(int argc, char** argv) {
    const Program program{"spatial_bench", "spatial"};
    const Options o = parseOptions(program, argc, argv);
    const CpuThreads cpuThreads(o.threads);
    const int threads = cpuThreads.count();
    char heading[128];
    std::snprintf(heading, sizeof heading, "spatial_bench: %d threads, best of %d, scale %g",
                  threads, o.repeat, o.scale);
    return runBench(program, o, threads, "", heading, [](const BenchSet& s, Context& c) {
        measureSet(CpuExec{}, s, c);
    });
}
