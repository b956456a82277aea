// gpu_mlt.cu — the GPU driver of many-chain PSSMLT (gpu_mlt.h): MltRenderer::Impl over device
// buffers, step for step the CPU driver (MltImpl in integrators/mlt/mlt_integrator.cpp) with the
// kernels launched by cuda/mlt_kernels.h. Launchers of the driver's own small kernels (pixel
// weights, chain permutation) are free functions: nvcc's extended lambdas must not be defined in
// private member functions. UNVERIFIED: compiled and linked for sm_90, never run on a GPU.
#include "cuda/gpu_mlt.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include <cuda_runtime.h>

#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"
#include "cuda/cuda_check.h"
#include "cuda/gpu_scene.h"
#include "cuda/mlt_kernels.h"
#include "cuda/parallel_for_cuda.h"

namespace caustica {
namespace gpu_mlt_kernels {

/// Relative target: importance[i] *= weight[pixel[i]] (the CPU's "mlt.bootstrap_target").
void applyPixelWeights(float* importance, const uint32_t* pixel, const float* weight, uint64_t count) {
    parallelForCuda("mlt.bootstrap_target", count,
                    [=] __device__(size_t i) { importance[i] *= weight[pixel[i]]; });
}

/// `elementBytes` bytes moved as one value.
template <size_t N>
struct Blob {
    unsigned char bytes[N];
};

template <size_t N>
void permuteRowsT(const void* src, void* dst, uint32_t chains, size_t rows, const uint32_t* order) {
    const Blob<N>* s = static_cast<const Blob<N>*>(src);
    Blob<N>* d = static_cast<Blob<N>*>(dst);
    const size_t n = chains;
    parallelForCuda("mlt.permute", n * rows, [=] __device__(size_t i) {
        const size_t row = i / n, c = i % n;
        d[i] = s[row * n + order[c]];
    });
}

static_assert(sizeof(Vec2f) == 8 && sizeof(Spectrum) == 12, "permuteRows covers 1, 2, 3, 4, 8, 12-byte elements");

/// Dimension-major per-chain arrays (element (row, chain) at row * chains + chain): dst(row, c) =
/// src(row, order[c]) for every row, elements of `elementBytes` bytes.
void permuteRows(const void* src, void* dst, size_t elementBytes, uint32_t chains, size_t rows,
                 const uint32_t* order) {
    switch (elementBytes) {
    case 1: return permuteRowsT<1>(src, dst, chains, rows, order);
    case 2: return permuteRowsT<2>(src, dst, chains, rows, order);
    case 3: return permuteRowsT<3>(src, dst, chains, rows, order);
    case 4: return permuteRowsT<4>(src, dst, chains, rows, order);
    case 8: return permuteRowsT<8>(src, dst, chains, rows, order);
    case 12: return permuteRowsT<12>(src, dst, chains, rows, order);
    default: throw Error("GPU MLT: no permutation kernel for " + std::to_string(elementBytes) + "-byte elements");
    }
}

}  // namespace gpu_mlt_kernels

namespace {

using Clock = std::chrono::steady_clock;

/// Waits for the device, then the seconds since t (kernel launches are asynchronous).
double secondsSince(Clock::time_point t) {
    CA_CUDA_CHECK(cudaDeviceSynchronize());
    return std::chrono::duration<double>(Clock::now() - t).count();
}

class GpuMltImpl final : public MltRenderer::Impl {
public:
    GpuMltImpl(const Scene& scene, const Bvh& bvh, const PathSettings& path, const MltSettings& s, uint64_t seed)
        : scene_(scene, bvh),
          film_(scene.film.filter, scene.film.width, scene.film.height),
          buf_(gpu_, s.chains, s.proposals, uint32_t(scene.film.width) * uint32_t(scene.film.height), s.splat) {
        settings = s;
        params_ = mltStepParams(scene, path, s, seed);
        pixels_ = uint32_t(params_.width) * uint32_t(params_.height);
        pixels = pixels_;

        const uint32_t n = s.chains;
        const uint32_t bounces = mltStoredBounces(path);
        // Compact store, dimension-major (coordinate d of chain c at d * chains + c): a warp's
        // threads read neighbouring chains' values of the same coordinate, which coalesces.
        store_.dims = mltStoredDims(bounces);
        fineSlots_ = kMltCameraDims + 4 * size_t(bounces);
        coarseSlots_ = 3 * size_t(bounces);
        fine_ = Buffer<uint8_t>(gpu_, std::max<size_t>(1, 3 * fineSlots_ * n));
        coarse_ = Buffer<uint16_t>(gpu_, std::max<size_t>(1, coarseSlots_ * n));
        store_.fine = fine_.data();
        store_.coarse = coarse_.data();
        store_.fineChainStride = 1;
        store_.fineDimStride = n;
        store_.coarseChainStride = 1;
        store_.coarseDimStride = n;

        if (s.sortEvery > 0) {
            mortonKeys_ = Buffer<uint64_t>(gpu_, n);
            order_ = Buffer<uint32_t>(gpu_, n);
            // One scratch array as large as the largest per-chain array; each is permuted into it
            // and copied back.
            const size_t largest = std::max({fine_.size(), coarse_.size() * sizeof(uint16_t),
                                             size_t(n) * sizeof(Spectrum), size_t(n) * sizeof(Vec2f)});
            permuteScratch_ = Buffer<uint8_t>(gpu_, largest);
        }
        stats.bytesPerChain = mltBytesPerChain(MltStateKind::Compact, bounces);
        stats.stateBytes = stats.bytesPerChain * n;
        stats.scratchBytes = buf_.scratchBytes() + mortonKeys_.size() * sizeof(uint64_t) +
                             order_.size() * sizeof(uint32_t) + permuteScratch_.size();
    }

    void bootstrap() override {
        const auto t0 = Clock::now();
        const uint32_t n = settings.chains;
        const uint64_t m = mltBootstrapCount(settings, pixels_);
        Buffer<float> importance(gpu_, m);
        Buffer<uint32_t> pixelOf(gpu_, m), rays(gpu_, m);
        const BvhIntersector accel = scene_.intersector();
        // Luminances first (params_.pixelWeight is still null), as on the CPU.
        launchMltBootstrap(scene_.view(), accel, params_, m, importance.data(), pixelOf.data(), rays.data());
        stats.rays += reduceSum(gpu_, rays.constSpan());

        std::vector<float> hostImportance;  // downloaded only where a host step reads it
        if (settings.target == MltTarget::Relative) {
            hostImportance = importance.toHost();
            const std::vector<uint32_t> hostPixel = pixelOf.toHost();
            const std::vector<float> weight =
                mltRelativePixelWeights(hostImportance.data(), hostPixel.data(), m, params_.width, params_.height);
            pixelWeight_ = Buffer<float>(gpu_, weight);
            params_.pixelWeight = pixelWeight_.data();  // device memory: the kernels read it
            gpu_mlt_kernels::applyPixelWeights(importance.data(), pixelOf.data(), pixelWeight_.data(), m);
            // The host copy gets the same products (one correctly rounded float multiply each).
            for (uint64_t i = 0; i < m; ++i) hostImportance[i] *= weight[hostPixel[i]];
        }
        // b = E[I]: the bootstrap mean (refined later by the large steps).
        const double sum = reduceSum(gpu_, importance.constSpan());
        stats.bootstrapSamples = m;
        b_.add(sum, double(m));
        stats.b = b_.b();
        if (!(sum > 0))
            throw Error("MLT: none of the " + std::to_string(m) +
                        " bootstrap paths carries light (the image is black); check the emitters");
        if (settings.start == MltStart::Bootstrap && hostImportance.empty()) hostImportance = importance.toHost();
        const std::vector<uint64_t> start =
            mltChainStarts(hostImportance.empty() ? nullptr : hostImportance.data(), m, n, settings.start, params_.seed);
        const Buffer<uint64_t> startIndex(gpu_, start);
        Buffer<uint32_t> startRays(gpu_, n);
        launchMltStart(scene_.view(), accel, view(), params_, startIndex.data(), startRays.data());
        stats.rays += reduceSum(gpu_, startRays.constSpan());
        stats.bootstrapSeconds = secondsSince(t0);
        started = true;
    }

    uint64_t iterate() override {
        MltStepParams p = params_;
        p.iteration = uint32_t(stats.iterations);
        p.b = float(stats.b);
        const MltChainView<CompactChainStore> v = view();

        return mltTimedIteration(
            stats, b_, settings, secondsSince, [&] { launchMltProposals(scene_.view(), scene_.intersector(), v, p); },
            [&] {
                launchMltAdvance(v, p);
                return buf_.reduceCounters(gpu_);  // on the device; each reduction waits for the advance
            },
            [&] { splat(); }, [&] { sortChains(); });
    }

    Image develop() const override {
        const std::vector<double> sums = buf_.image.toHost();  // cudaMemcpy waits for the splats
        return film_.develop(sums.data(), double(settings.chains) * settings.proposals * double(stats.iterations));
    }

private:
    MltChainView<CompactChainStore> view() { return buf_.view(store_); }
    MltSplatView splatView() { return buf_.splatView(film_, params_.width, params_.height); }

    void splat() {
        const MltSplatView v = splatView();
        if (settings.splat == MltSplatKind::Atomic) {
            launchMltSplatAtomic(v, pixels_);
            return;
        }
        launchMltSplatKeys(v, buf_.sortKeys.data(), buf_.sortValues.data());
        radixSortPairs(gpu_, buf_.sortKeys.span(), buf_.sortValues.span(), 32);
        launchMltSplatGather(v, buf_.pixelStart.data(), pixels_);
    }

    /// The CPU's sortChains: Morton keys, a stable radix sort of (key, chain), and every per-chain
    /// array permuted into the sorted order (a chain keeps its random stream index c).
    void sortChains() {
        launchMltMortonKeys(view(), params_.width, params_.height, mortonKeys_.data(), order_.data());
        radixSortPairs(gpu_, mortonKeys_.span(), order_.span(), 64);
        permute(buf_.pos.data(), sizeof(Vec2f), 1);
        permute(buf_.value.data(), sizeof(Spectrum), 1);
        permute(buf_.importance.data(), sizeof(float), 1);
        permute(buf_.usedDims.data(), sizeof(uint16_t), 1);
        if (fineSlots_ > 0) permute(fine_.data(), 3, fineSlots_);
        if (coarseSlots_ > 0) permute(coarse_.data(), sizeof(uint16_t), coarseSlots_);
    }
    /// Permutes `rows` dimension-major rows of `elementBytes`-byte elements in place (through the
    /// scratch array).
    void permute(void* data, size_t elementBytes, size_t rows) {
        const size_t bytes = elementBytes * rows * settings.chains;
        gpu_mlt_kernels::permuteRows(data, permuteScratch_.data(), elementBytes, settings.chains, rows,
                                     order_.data());
        CA_CUDA_CHECK(cudaMemcpy(data, permuteScratch_.data(), bytes, cudaMemcpyDeviceToDevice));
    }

    Device gpu_ = Device::cuda();
    GpuScene scene_;
    MltStepParams params_;
    uint32_t pixels_ = 0;
    MltFilm film_;
    CompactChainStore store_;
    size_t fineSlots_ = 0, coarseSlots_ = 0;
    Buffer<uint8_t> fine_, permuteScratch_;
    Buffer<uint16_t> coarse_;
    MltChainBuffers buf_;
    Buffer<float> pixelWeight_;
    Buffer<uint32_t> order_;
    Buffer<uint64_t> mortonKeys_;
    MltNormalisation b_;
};

}  // namespace

std::unique_ptr<MltRenderer> makeGpuMltRenderer(const Scene& scene, const Bvh& bvh, const PathSettings& path,
                                                const MltSettings& settings, uint64_t seed) {
    validateMltSettings(settings);
    // Before any GPU work: a float-state request fails fast with a one-line error.
    if (settings.state != MltStateKind::Compact)
        throw Error("--mlt-state float is not available on the GPU (its path-tracing kernels are compiled for "
                    "the compact state only); use --mlt-state compact or --device cpu");
    if (uint64_t(settings.chains) * (uint64_t(settings.proposals) + 1) > uint64_t(0xffffffffu))
        throw Error("GPU MLT: chains x (proposals + 1) must stay below 2^32");
    return std::make_unique<MltRenderer>(std::make_unique<GpuMltImpl>(scene, bvh, path, settings, seed));
}

}  // namespace caustica
