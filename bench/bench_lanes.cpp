// bench_lanes.cpp — the shading code generic over the lane type (util/lane.h) run one path at a
// time (F = float, what the GPU and today's CPU shade stage run) and four at a time (F = Float4,
// SSE), on the same inputs held struct-of-arrays: what the per-bounce steps gain from lanes before
// any gathering of path state is paid for.
//
//   bench_lanes [--benchmark_repetitions=N]
// Benchmarks, each over 4096 bounces (items_per_second = bounces/s):
//   diffuse_direction/{float,float4}  a cosine-weighted direction (concentric disk) from u and
//                                     turned into the world by the frame of the normal n
//   power_heuristic/{float,float4}    the MIS weight of two pdfs
#include <benchmark/benchmark.h>

#include <vector>

#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"

using namespace caustica;

namespace {

constexpr size_t kCount = 4096;

struct Inputs {
    std::vector<float> ux, uy, nx, ny, nz, pdfA, pdfB;
    std::vector<float> out[3];

    Inputs() {
        for (size_t i = 0; i < kCount; ++i) {
            IndependentSampler rng(i, 0, 42);
            ux.push_back(rng.get1D());
            uy.push_back(rng.get1D());
            const Vec3f n = sampleUniformSphere(rng.get2D());
            nx.push_back(n.x);
            ny.push_back(n.y);
            nz.push_back(n.z);
            pdfA.push_back(rng.get1D() * 4);
            pdfB.push_back(rng.get1D() * 4);
        }
        for (auto& o : out) o.resize(kCount);
    }
};

const Inputs& inputs() {
    static const Inputs in;
    return in;
}

template <class F>
F load(const std::vector<float>& v, size_t i) {
    if constexpr (std::is_same_v<F, float>)
        return v[i];
    else
        return F::loadUnaligned(v.data() + i);
}
template <class F>
void store(std::vector<float>& v, size_t i, F f) {
    if constexpr (std::is_same_v<F, float>)
        v[i] = f;
    else
        f.store(v.data() + i);
}

template <class F>
void diffuseDirection(benchmark::State& state) {
    Inputs in = inputs();
    constexpr size_t W = size_t(LaneTraits<F>::width);
    for (auto _ : state) {
        for (size_t i = 0; i < kCount; i += W) {
            const Vec3Of<F> n{load<F>(in.nx, i), load<F>(in.ny, i), load<F>(in.nz, i)};
            Vec3Of<F> s, t;
            orthonormalBasis<F>(n, s, t);
            const Vec3Of<F> local = sampleCosineHemisphere<F>(Vec2Of<F>{load<F>(in.ux, i), load<F>(in.uy, i)});
            const Vec3Of<F> w = frameToWorld<F>(s, t, n, local);
            store(in.out[0], i, w.x);
            store(in.out[1], i, w.y);
            store(in.out[2], i, w.z);
        }
        benchmark::DoNotOptimize(in.out[0].data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kCount));
}

template <class F>
void powerHeuristicBench(benchmark::State& state) {
    Inputs in = inputs();
    constexpr size_t W = size_t(LaneTraits<F>::width);
    for (auto _ : state) {
        for (size_t i = 0; i < kCount; i += W)
            store(in.out[0], i, powerHeuristic<F>(load<F>(in.pdfA, i), load<F>(in.pdfB, i)));
        benchmark::DoNotOptimize(in.out[0].data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kCount));
}

BENCHMARK(diffuseDirection<float>)->Name("diffuse_direction/float");
BENCHMARK(diffuseDirection<Float4>)->Name("diffuse_direction/float4");
BENCHMARK(powerHeuristicBench<float>)->Name("power_heuristic/float");
BENCHMARK(powerHeuristicBench<Float4>)->Name("power_heuristic/float4");

}  // namespace

BENCHMARK_MAIN();
