// bench_gpu_spatial.cu — spatial_bench on the GPU (issue 19): build time, bytes per point and
// queries per second of every photon lookup structure (src/caustica/spatial/) for every query
// type and point set, with the structures built by S::build(GpuExec, ...) and the queries launched
// as CUDA grids over device buffers. The point sets, the structure list, the query kernels, the
// totals check and the CSV are spatial_bench_core.h's, the very code spatial_bench runs on the
// CPU; the point sets come from the same CPU SPPM renders (on the host's threads), so the figures
// compare row by row with spatial_bench's.
//
//   bench_gpu_spatial [--sets uniform,cornell-water,glass-caustic,water-1080p] [--repeat 3]
//                     [--iterations 8] [--photons 262144] [--threads N] [--scale 1]
//                     [--structures NAME,...] [--csv FILE]
//
// Options as spatial_bench's; --threads bounds the host's threads (the SPPM renders and the CPU
// reference below). Each build and query type runs once untimed (the first launch of a kernel
// loads its module), then --repeat times timed with CUDA events; the best is reported. Bytes per
// point: the structure's device memory (memoryBytes()) / points.
// Correctness: the totals (result counts and index sums, copied back) of every GPU structure and
// repeat must agree exactly, as in spatial_bench, and agree with those of the uniform grid on the
// CPU ("cpu:grid") up to the rounding of fused multiply-adds (kRoundingTolerance below); a
// disagreement prints an ERROR line and the program exits with status 1 after writing all rows.
// CSV (default bench/results/spatial-gpu-YYYY-MM-DD.csv): spatial_bench's columns with `threads`
// 0 (the queries ran on the GPU) and a last column `device` (the GPU's name).
// The table starts with a "== " heading (scripts/gpu-check prints a benchmark's log from there).
// The run without arguments (what gpu-check does) is the full size, like spatial_bench's: 13 s on
// an H200 with a 16-core host (2026-11-27), most of it the CPU SPPM renders (about 80
// CPU-seconds: 40 s on 2 cores); --sets uniform --scale 0.1 --repeat 1 is a smoke run of seconds.
// Without a CUDA GPU it prints why and exits 0, measuring nothing.
#include <algorithm>
#include <cstdio>
#include <string>

#include "cuda/cuda_backend.h"
#include "spatial_bench_core.h"

using namespace caustica;
using namespace caustica::spatial_bench;

namespace {

/// How far the GPU's totals may stray from the CPU's. Written when the predicates' products could
/// be fused into multiply-adds on the GPU and not on the CPU; since util/unfused.h they round the
/// same on both, and the H200 run of 2026-11-27 found every set and query equal (the tolerance
/// printed no "rounding" line). Kept until a GPU run shows the check can be made exact; a
/// structure that skips a cell or a node loses far more than 1e-4 of the results.
constexpr double kRoundingTolerance = 1e-4;

/// The CPU's reference: the uniform grid built and queried on the CPU for every query of s,
/// compared with the GPU structures' totals (after they ran: they are the exact reference).
void checkAgainstCpu(const BenchSet& s, AgreementCheck& agreement) {
    const PreparedSet<CpuExec> p(s);
    const UniformGrid grid = UniformGrid::build(CpuExec{}, p.points());
    for (Query q : queriesOf(s)) {
        QueryOutputs<CpuExec> out(s.queries.size());
        runQueries(CpuExec{}, grid.view(), q, p, out);
        const Totals cpu = totalsOf(out);
        const uint64_t allowed =
            std::max<uint64_t>(2, uint64_t(kRoundingTolerance * double(cpu.results)));
        agreement.checkNear(s.name, q, "cpu:grid", cpu, allowed, s.positions.size());
    }
}

}  // namespace

int main(int argc, char** argv) {
    const Program program{"bench_gpu_spatial", "spatial-gpu"};
    const Options o = parseOptions(program, argc, argv);
    registerCudaBackend();
    if (cudaDeviceCountOrZero() == 0) {
        std::printf(
            "bench_gpu_spatial: no CUDA GPU found (or no driver): skipped, nothing measured\n");
        return 0;
    }
    const CpuThreads hostThreads(o.threads);
    const std::string device = cudaDeviceDescription();
    char heading[512];
    std::snprintf(heading, sizeof heading,
                  "== bench_gpu_spatial: photon lookup structures on %s, best of %d after 1 "
                  "warm-up, scale %g (point sets and the cpu:grid check on %d host threads)",
                  device.c_str(), o.repeat, o.scale, hostThreads.count());
    return runBench(program, o, 0, device, heading, [](const BenchSet& s, Context& c) {
        measureSet(GpuExec{}, s, c);
        checkAgainstCpu(s, c.agreement);
    });
}
