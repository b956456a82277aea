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
//   diffuse_nee/{float,float4}        next-event estimation at a diffuse point lit by a rectangle
//                                     light: a point on the light, its solid-angle pdf and direction,
//                                     the frame of the normal, the BSDF's value and pdf, the MIS
//                                     weight and the contribution (cornell-box's every bounce)
#include <benchmark/benchmark.h>

#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/scene/light.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"

using namespace caustica;

namespace {

constexpr size_t kCount = 4096;

struct Inputs {
    std::vector<float> ux, uy, nx, ny, nz, pdfA, pdfB, px, py, pz, wox, woy, woz, refl;
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
            // A point in a unit box under the light, looked at from its normal's side.
            px.push_back(rng.get1D() * 2 - 1);
            py.push_back(rng.get1D() * 1.8f - 1);
            pz.push_back(rng.get1D() * 2 - 1);
            const Vec3f wo = normalize(n + sampleUniformSphere(rng.get2D()) * 0.5f);
            wox.push_back(wo.x);
            woy.push_back(wo.y);
            woz.push_back(wo.z);
            refl.push_back(rng.get1D());
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

template <class F>
Vec3Of<F> broadcast3(Vec3f v) {
    return Vec3Of<F>{lane::splat<F>(v.x), lane::splat<F>(v.y), lane::splat<F>(v.z)};
}

template <class F>
void diffuseNee(benchmark::State& state) {
    Inputs in = inputs();
    constexpr size_t W = size_t(LaneTraits<F>::width);
    const Vec3Of<F> corner = broadcast3<F>(Vec3f(-0.25f, 0.99f, -0.25f)), edgeU = broadcast3<F>(Vec3f(0.5f, 0, 0)),
                    edgeV = broadcast3<F>(Vec3f(0, 0, 0.5f)), lightN = broadcast3<F>(Vec3f(0, -1, 0));
    const F area = lane::splat<F>(0.25f), selPdf = lane::splat<F>(1), le = lane::splat<F>(17);
    for (auto _ : state) {
        for (size_t i = 0; i < kCount; i += W) {
            const Vec3Of<F> refP{load<F>(in.px, i), load<F>(in.py, i), load<F>(in.pz, i)};
            const Vec3Of<F> n{load<F>(in.nx, i), load<F>(in.ny, i), load<F>(in.nz, i)};
            const Vec3Of<F> wo{load<F>(in.wox, i), load<F>(in.woy, i), load<F>(in.woz, i)};
            const F r = load<F>(in.refl, i);
            const Vec3Of<F> p = light_detail::parallelogramPoint<F>(corner, edgeU, edgeV,
                                                                    Vec2Of<F>{load<F>(in.ux, i), load<F>(in.uy, i)});
            const F solidAnglePdf = light_detail::areaToSolidAngle<F>(refP, p, lightN, area);
            Vec3Of<F> wi;
            F dist, lightPdf;
            const MaskOf<F> lit = light_detail::areaLightDirection<F>(refP, p, solidAnglePdf, selPdf, wi, dist, lightPdf);
            Vec3Of<F> s, t;
            orthonormalBasis<F>(n, s, t);
            const Vec3Of<F> woLocal = frameToLocal<F>(s, t, n, wo), wiLocal = frameToLocal<F>(s, t, n, wi);
            const SpectrumOf<F> f = bsdf_detail::diffuseEvalLocal<F>(SpectrumOf<F>{r, r, r}, woLocal, wiLocal);
            const F bsdfPdf = bsdf_detail::diffusePdfLocal<F>(woLocal, wiLocal);
            const F weight = powerHeuristic<F>(lightPdf, bsdfPdf) / lightPdf * le;
            const F zero = lane::splat<F>(0);
            store(in.out[0], i, lane::select(lit, f.r * weight, zero));
            store(in.out[1], i, lane::select(lit, f.g * weight, zero));
            store(in.out[2], i, lane::select(lit, f.b * weight, zero));
        }
        benchmark::DoNotOptimize(in.out[0].data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kCount));
}

BENCHMARK(diffuseDirection<float>)->Name("diffuse_direction/float");
BENCHMARK(diffuseDirection<Float4>)->Name("diffuse_direction/float4");
BENCHMARK(powerHeuristicBench<float>)->Name("power_heuristic/float");
BENCHMARK(powerHeuristicBench<Float4>)->Name("power_heuristic/float4");
BENCHMARK(diffuseNee<float>)->Name("diffuse_nee/float");
BENCHMARK(diffuseNee<Float4>)->Name("diffuse_nee/float4");

}  // namespace

BENCHMARK_MAIN();
