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

#include "caustica/integrators/mlt/mlt_bootstrap.h"
#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_checkpoint.h"
#include "caustica/integrators/mlt/mlt_gpu_memory.h"
#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"
#include "cuda/cuda_backend.h"
#include "cuda/cuda_check.h"
#include "cuda/gpu_scene.h"
#include "cuda/mlt_kernels.h"
#include "cuda/parallel_for_cuda.h"

namespace caustica {
namespace gpu_mlt_kernels {

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
        : Impl(scene, path, s, seed),
          scene_(scene, bvh),
          film_(scene.film.filter, scene.film.width, scene.film.height),
          buf_(gpu_, s.chains, s.proposals, pixels_, s.splat, mltSplatBatch(s, pixels_)) {
        const uint32_t n = s.chains;
        const uint32_t bounces = mltStoredBounces(path);
        // Compact store, dimension-major (coordinate d of chain c at d * chains + c): a warp's
        // threads read neighbouring chains' values of the same coordinate, which coalesces.
        store_.dims = mltStoredDims(bounces);
        fineSlots_ = kMltCameraDims + 4 * size_t(bounces);
        coarseSlots_ = 3 * size_t(bounces);
        fine_ = Buffer<uint8_t>(gpu_, std::max<size_t>(1, 3 * fineSlots_ * n));
        coarse_ = Buffer<uint16_t>(gpu_, std::max<size_t>(1, coarseSlots_ * n));
        fine_.zero();  // slots past a chain's path stay unwritten: keep checkpoints reproducible
        coarse_.zero();
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
            permuteScratch_ = Buffer<uint8_t>(gpu_, mltGpuPermuteScratchBytes(n, bounces));
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

        // The plan (pixel weights, b, starts) is made on the host, as on the CPU.
        // The pixels matter to the relative target only.
        std::vector<float> hostImportance = importance.toHost();
        const std::vector<uint32_t> hostPixel =
            settings.target == MltTarget::Relative ? pixelOf.toHost() : std::vector<uint32_t>{};
        const MltBootstrapPlan plan =
            planMltBootstrap(hostImportance, hostPixel, settings, params_.width, params_.height, params_.seed);
        if (!plan.pixelWeight.empty()) {
            pixelWeight_ = Buffer<float>(gpu_, plan.pixelWeight);
            params_.pixelWeight = pixelWeight_.data();  // device memory: the kernels read it
        }
        adoptMltBootstrap(plan, m, b_, stats);
        const std::vector<uint64_t>& start = plan.starts;
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
        p.b = float(b_.b0);
        const MltChainView<CompactChainStore> v = buf_.view(store_, stats.iterations);

        return mltTimedIteration(
            stats, b_, settings, buf_.batch, secondsSince,
            [&] { launchMltProposals(scene_.view(), scene_.intersector(), v, p); },
            [&] {
                launchMltAdvance(v, p);
                return buf_.reduceCounters(gpu_);  // on the device; each reduction waits for the advance
            },
            [&] { splat(buf_.batch, buf_.image.data()); }, [&] { sortChains(); });
    }

    Image develop() override {
        const double total = double(settings.chains) * settings.proposals * double(stats.iterations);
        const uint64_t pending = buf_.pendingIterations(stats.iterations);
        if (pending == 0) {
            const std::vector<double> sums = buf_.image.toHost();  // cudaMemcpy waits for the splats
            return film_.develop(sums.data(), b_, total);
        }
        // The unfinished batch goes into a device copy of the sums, as on the CPU.
        Buffer<double> sums(gpu_, buf_.image.toHost());
        splat(pending, sums.data());
        return film_.develop(sums.toHost().data(), b_, total);
    }

    // Checkpoints hold the CPU driver's chain-major store: the dimension-major arrays are
    // transposed on the host (mlt_checkpoint.h), so a checkpoint resumes on either driver.
    void save(std::ostream& out) const override {
        MltCheckpoint c = mltCheckpointOf(stats, b_, buf_);
        c.pixelWeight = pixelWeight_.toHost();
        c.fine = mltTransposeCells(fine_.toHost(), fineSlots_, settings.chains, 3);
        c.coarse = mltTransposeCells(coarse_.toHost(), coarseSlots_, settings.chains, 1);
        writeMltCheckpoint(out, checkpointKeys(), c);
    }

    void load(std::istream& in) override {
        const MltCheckpointSizes sizes = mltCheckpointSizes(settings, pixels_, buf_, fine_.size(), coarse_.size(), 0);
        const MltCheckpoint c = readMltCheckpoint(in, checkpointKeys(), sizes, stats);  // throws before any change
        restoreMltCheckpoint(c, stats, b_, buf_);
        fine_.copyFromHost(mltTransposeCells(c.fine, settings.chains, fineSlots_, 3));
        coarse_.copyFromHost(mltTransposeCells(c.coarse, settings.chains, coarseSlots_, 1));
        // The kernels read the weights from device memory through params_.
        pixelWeight_ = c.pixelWeight.empty() ? Buffer<float>() : Buffer<float>(gpu_, c.pixelWeight);
        params_.pixelWeight = pixelWeight_.empty() ? nullptr : pixelWeight_.data();
        started = true;
    }

private:
    MltCheckpointKeys checkpointKeys() const {
        return mltCheckpointKeys(params_, settings, store_.dims, film_.filter());
    }

    MltChainView<CompactChainStore> view() { return buf_.view(store_); }

    /// Adds the splats of the first `iterations` slots to `target` (device memory).
    void splat(uint64_t iterations, double* target) {
        const MltSplatView v = buf_.splatView(film_, params_.width, params_.height, iterations, target);
        if (settings.splat == MltSplatKind::Atomic) {
            launchMltSplatAtomic(v, pixels_);
            return;
        }
        launchMltSplatKeys(v, buf_.sortKeys.data(), buf_.sortValues.data());
        radixSortPairs(gpu_, Span<uint32_t>(buf_.sortKeys.data(), v.count),
                       Span<uint32_t>(buf_.sortValues.data(), v.count), 32);
        launchMltSplatGather(v, buf_.pixelStart.data(), pixels_);
    }

    /// The CPU's sortChains: Morton keys, a stable radix sort of (key, chain), and every per-chain
    /// array permuted into the sorted order (the state now at position c draws from stream c).
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

/// Refuses (one line) a render whose estimated device memory exceeds the free memory; without a
/// GPU there is nothing to compare with and the allocation reports the error.
void checkGpuMltMemory(const Scene& scene, const Bvh& bvh, const PathSettings& path, const MltSettings& settings) {
    size_t freeBytes = 0, totalBytes = 0;
    if (!cudaMemoryInfo(freeBytes, totalBytes)) return;
    const GpuMemoryEstimate sceneBytes = estimateGpuMemory(gpuRenderSizes(scene, bvh, 1, GpuPathMode::Megakernel));
    const uint32_t pixels = uint32_t(scene.film.width) * uint32_t(scene.film.height);
    const MltGpuMemoryEstimate mlt = estimateMltGpuMemory(settings, mltStoredBounces(path), pixels);
    const size_t need = sceneBytes.scene + sceneBytes.bvh + mlt.total();
    if (need <= freeBytes) return;
    throw Error("GPU memory: MLT needs about " + formatBytes(need) + " (scene and BVH " +
                formatBytes(sceneBytes.scene + sceneBytes.bvh) + ", chains " +
                formatBytes(mlt.chainState + mlt.chainScratch + mlt.chainSort) + ", bootstrap " +
                formatBytes(mlt.bootstrap) + ") but only " + formatBytes(freeBytes) + " is free on " +
                cudaDeviceDescription() + "; lower --mlt-chains or --mlt-bootstrap, or use --device cpu");
}

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
    checkGpuMltMemory(scene, bvh, path, settings);
    return std::make_unique<MltRenderer>(std::make_unique<GpuMltImpl>(scene, bvh, path, settings, seed));
}

}  // namespace caustica
