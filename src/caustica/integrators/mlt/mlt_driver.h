// mlt_driver.h — the one driver of many-chain PSSMLT, for every device: bootstrap, proposals,
// chain advance, splats (atomic or sorted), Morton sorting of the chains, develop and
// checkpoints, written once against launch.h. Templates only: mlt_driver.cpp instantiates them
// for the device it is compiled for (g++: CPU; nvcc through cuda/*_driver.cu: GPU).
//
// What differs between devices is data, not logic: the chain store's layout (chain-major on the
// CPU, where a chain's coordinates share cache lines; dimension-major on a GPU, where a warp's
// threads then read neighbouring chains' values of one coordinate, which coalesces) and where the
// kernels write (host or device memory).
#pragma once

#include <algorithm>
#include <chrono>
#include <istream>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "caustica/accel/device_scene.h"
#include "caustica/integrators/mlt/mlt_bootstrap.h"
#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_checkpoint.h"
#include "caustica/integrators/mlt/mlt_gpu_memory.h"
#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/integrators/mlt/mlt_kernel.h"
#include "caustica/integrators/mlt/mlt_rank_checkpoint.h"
#include "caustica/integrators/mlt/mlt_ranks.h"
#include "caustica/parallel/backend.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"

namespace caustica {

/// The MLT driver of the device of `Exec` (defined per device by mlt_driver.cpp). The scene and
/// accel (a Bvh one for a GPU) outlive it. Throws caustica::Error for settings it cannot run.
/// `comm`: the ranks the chains are split over (mlt_impl.h; one process by default).
template <class Exec>
std::unique_ptr<MltRenderer::Impl> makeMltDriver(const Scene& scene, const Accel& accel, const PathSettings& path,
                                                 const MltSettings& settings, uint64_t seed,
                                                 Communicator& comm = singleProcess());

// Kernel launchers: free functions, as nvcc's kernel lambdas must not be defined in private members.
namespace mlt_driver_detail {

/// Bootstrap samples [first, first + count) (their global indices key their streams).
template <class Exec, class Store, class Intersector>
void bootstrapKernel(Exec exec, const SceneView& scene, const Intersector& accel, const MltStepParams& params,
                     uint64_t first, uint64_t count, float* importance, uint32_t* pixel, uint32_t* rays) {
    constexpr uint64_t G = mltItemsPerLaunch<Intersector>();
    launch(exec, "mlt.bootstrap", size_t((count + G - 1) / G), [=] CA_HD(size_t g) {
        const uint64_t i = g * G;
        const uint32_t n = uint32_t(min(G, count - i));
        bootstrapImportances<Store>(scene, accel, params, first + i, n, importance + i, pixel + i, rays + i);
    });
}

template <class Exec, class Store, class Intersector>
void startKernel(Exec exec, const SceneView& scene, const Intersector& accel, const MltChainView<Store>& chains,
                 const MltStepParams& params, const uint64_t* bootstrapIndex, uint32_t* rays) {
    launch(exec, "mlt.start", chains.chains, [=] CA_HD(size_t c) {
        uint32_t r = 0;
        startChain(scene, accel, chains, params, uint32_t(c), bootstrapIndex[c], r);
        rays[c] = r;
    });
}

template <class Exec, class Store, class Intersector>
void proposalKernel(Exec exec, const SceneView& scene, const Intersector& accel, const MltChainView<Store>& chains,
                    const MltStepParams& params) {
    constexpr uint32_t G = mltItemsPerLaunch<Intersector>();
    const uint32_t items = chains.chains * params.proposals;
    launch(exec, "mlt.propose", size_t((items + G - 1) / G), [=] CA_HD(size_t g) {
        const uint32_t first = uint32_t(g) * G;
        traceProposals(scene, accel, chains, params, first, min(G, items - first));
    }, G > 1 ? 1 : 16);
}

template <class Exec, class Store>
void advanceKernel(Exec exec, const MltChainView<Store>& chains, const MltStepParams& params) {
    launch(exec, "mlt.advance", chains.chains, [=] CA_HD(size_t c) { advanceChain(chains, params, uint32_t(c)); },
           256);
}

template <class Exec, class Store>
void mortonKernel(Exec exec, const MltChainView<Store>& chains, int width, int height, uint64_t* keys,
                  uint32_t* order) {
    launch(exec, "mlt.morton", chains.chains, [=] CA_HD(size_t c) {
        keys[c] = mltMortonKey(chains, uint32_t(c), width, height);
        order[c] = uint32_t(c);
    }, 256);
}

template <class Exec>
void splatAtomicKernels(Exec exec, const MltSplatView& v, uint32_t pixels) {
    launch(exec, "mlt.splat_atomic", v.count, [=] CA_HD(size_t i) { splatAtomic(v, uint32_t(i)); }, 256);
    launch(exec, "mlt.splat_flush", pixels, [=] CA_HD(size_t p) { flushAtomicPixel(v, uint32_t(p)); }, 256);
}

template <class Exec>
void splatKeyKernel(Exec exec, const MltSplatView& v, uint32_t* keys, uint32_t* values) {
    launch(exec, "mlt.splat_keys", v.count, [=] CA_HD(size_t i) {
        keys[i] = splatPixel(v, v.splats[i]);
        values[i] = uint32_t(i);
    }, 256);
}

template <class Exec>
void splatGatherKernels(Exec exec, const MltSplatView& v, uint32_t* pixelStart, uint32_t pixels) {
    const uint32_t* sorted = v.sortedPixel;
    const uint32_t count = v.count;
    launch(exec, "mlt.splat_starts", size_t(pixels) + 1,
           [=] CA_HD(size_t p) { findPixelStart(pixelStart, sorted, count, uint32_t(p)); }, 256);
    launch(exec, "mlt.splat_gather", pixels, [=] CA_HD(size_t p) { gatherSplats(v, uint32_t(p)); }, 64);
}

/// `elementBytes` bytes moved as one value.
template <size_t N>
struct Blob {
    unsigned char bytes[N];
};

/// dst(row, c) = src(row, order[c]) for `rows` rows of `chains` elements of N bytes, element
/// (row, c) at row * rowStride + c * chainStride.
template <class Exec, size_t N>
void permuteKernel(Exec exec, const void* src, void* dst, uint32_t chains, size_t rows, size_t rowStride,
                   size_t chainStride, const uint32_t* order) {
    const Blob<N>* s = static_cast<const Blob<N>*>(src);
    Blob<N>* d = static_cast<Blob<N>*>(dst);
    const size_t n = chains;
    launch(exec, "mlt.permute", n * rows, [=] CA_HD(size_t i) {
        const size_t row = i / n, c = i % n;
        d[row * rowStride + c * chainStride] = s[row * rowStride + size_t(order[c]) * chainStride];
    }, 1024);
}

static_assert(sizeof(Vec2f) == 8 && sizeof(Spectrum) == 12, "permute covers 1, 2, 3, 4, 8, 12-byte elements");

template <class Exec>
void permute(Exec exec, const void* src, void* dst, size_t elementBytes, uint32_t chains, size_t rows,
             size_t rowStride, size_t chainStride, const uint32_t* order) {
    switch (elementBytes) {
    case 1: return permuteKernel<Exec, 1>(exec, src, dst, chains, rows, rowStride, chainStride, order);
    case 2: return permuteKernel<Exec, 2>(exec, src, dst, chains, rows, rowStride, chainStride, order);
    case 3: return permuteKernel<Exec, 3>(exec, src, dst, chains, rows, rowStride, chainStride, order);
    case 4: return permuteKernel<Exec, 4>(exec, src, dst, chains, rows, rowStride, chainStride, order);
    case 8: return permuteKernel<Exec, 8>(exec, src, dst, chains, rows, rowStride, chainStride, order);
    case 12: return permuteKernel<Exec, 12>(exec, src, dst, chains, rows, rowStride, chainStride, order);
    default: throw Error("MLT: no permutation kernel for " + std::to_string(elementBytes) + "-byte elements");
    }
}

}  // namespace mlt_driver_detail

template <class Exec, class Store>
class MltDriver final : public MltRenderer::Impl {
    static constexpr bool kCompact = std::is_same_v<Store, CompactChainStore>;
    /// Dimension-major store on a GPU (coalesced reads), chain-major on the CPU.
    static constexpr bool kDimensionMajor = Exec::kind != DeviceKind::Cpu;

public:
    /// settings.chains in all over the ranks of `comm`; this rank keeps localChains() of them.
    MltDriver(const Scene& scene, const Accel& accel, const PathSettings& path, const MltSettings& s, uint64_t seed,
              Communicator& comm)
        : Impl(scene, path, s, seed, comm),
          scene_(scene, accel, device()),
          film_(scene.film.filter, scene.film.width, scene.film.height, scene.film.eyeWidth),
          buf_(device(), localChains_, s.proposals, pixels_, s.splat, mltSplatBatch(s, pixels_)) {
        const uint32_t n = localChains_;
        const uint32_t bounces = mltStoredBounces(path);
        store_.dims = mltStoredDims(bounces);
        if constexpr (kCompact) {
            slots_[0] = kMltCameraDims + 4 * size_t(bounces);  // fine
            slots_[1] = 3 * size_t(bounces);                    // coarse
            fine_ = Buffer<uint8_t>(device(), std::max<size_t>(1, 3 * slots_[0] * n));
            coarse_ = Buffer<uint16_t>(device(), std::max<size_t>(1, slots_[1] * n));
            fine_.zero();  // slots past a chain's path stay unwritten: keep checkpoints reproducible
            coarse_.zero();
            store_.fineChainStride = kDimensionMajor ? 1 : slots_[0];
            store_.fineDimStride = kDimensionMajor ? n : 1;
            store_.coarseChainStride = kDimensionMajor ? 1 : slots_[1];
            store_.coarseDimStride = kDimensionMajor ? n : 1;
        } else {
            slots_[0] = store_.dims;
            values_ = Buffer<float>(device(), std::max<size_t>(1, size_t(store_.dims) * n));
            values_.zero();
            store_.chainStride = kDimensionMajor ? 1 : store_.dims;
            store_.dimStride = kDimensionMajor ? n : 1;
        }
        bindStore();
        if (s.sortEvery > 0) {
            mortonKeys_ = Buffer<uint64_t>(device(), n);
            order_ = Buffer<uint32_t>(device(), n);
            permuteScratch_ = Buffer<uint8_t>(device(), permuteScratchBytes(bounces));
        }
        stats.bytesPerChain = mltBytesPerChain(kCompact ? MltStateKind::Compact : MltStateKind::Float, bounces);
        stats.stateBytes = stats.bytesPerChain * n;
        stats.scratchBytes = buf_.scratchBytes() + mortonKeys_.size() * sizeof(uint64_t) +
                             order_.size() * sizeof(uint32_t) + permuteScratch_.size();
    }

    void bootstrap() override {
        using namespace mlt_driver_detail;
        const auto t0 = MltClock::now();
        const uint32_t n = localChains_;
        const uint64_t m = mltBootstrapCount(settings, pixels_);
        // This rank's share of the samples (all of them in one process), by global index.
        const MltShare share = mltShareOf(m, comm_.rank(), comm_.size());
        Buffer<float> importance(device(), share.count);
        Buffer<uint32_t> pixelOf(device(), share.count), rays(device(), share.count);
        // Luminances first (params_.pixelWeight is still null).
        scene_.visit(Exec{}, [&](const auto& intersector) {
            bootstrapKernel<Exec, Store>(Exec{}, scene_.view(), intersector, params_, share.first, share.count,
                                         importance.data(), pixelOf.data(), rays.data());
        });
        stats.rays += reduceSum(device(), rays.constSpan());

        // The plan (pixel weights, b, starts) is made on the host from all M samples (gathered
        // from the ranks: every rank makes one process's plan); the pixels matter to the
        // relative target only.
        std::vector<float> hostImportance = importance.toHost();  // the plan may rescale it
        std::vector<uint32_t> hostPixel =
            settings.target == MltTarget::Relative ? pixelOf.toHost() : std::vector<uint32_t>{};
        if (comm_.size() > 1) gatherMltBootstrap(comm_, hostImportance, hostPixel);
        const MltBootstrapPlan plan =
            planMltBootstrap(hostImportance, hostPixel, settings, params_.width, params_.height, params_.seed,
                             film_.eyeWidth());
        setPixelWeight(plan.pixelWeight);
        adoptMltBootstrap(plan, m, b_, stats);
        pending_.clear();

        // This rank's chains start where one process's chains of the same global index do.
        const Buffer<uint64_t> startIndex(
            device(), std::vector<uint64_t>(plan.starts.begin() + chainFirst(),
                                            plan.starts.begin() + chainFirst() + std::ptrdiff_t(n)));
        Buffer<uint32_t> startRays(device(), n);
        scene_.visit(Exec{}, [&](const auto& intersector) {
            startKernel(Exec{}, scene_.view(), intersector, view(), params_, startIndex.data(), startRays.data());
        });
        stats.rays += reduceSum(device(), startRays.constSpan());
        stats.bootstrapSeconds = secondsSince(t0);
        started = true;
    }

    uint64_t iterate() override {
        using namespace mlt_driver_detail;
        MltStepParams p = params_;
        p.iteration = uint32_t(stats.iterations);
        p.b = float(b_.b0);
        const MltChainView<Store> v = buf_.view(store_, stats.iterations);
        const uint64_t rays = mltTimedIteration(
            stats, b_, settings, buf_.batch, [](MltClock::time_point t) { return secondsSince(t); },
            [&] {
                scene_.visit(Exec{}, [&](const auto& intersector) {
                    proposalKernel(Exec{}, scene_.view(), intersector, v, p);
                });
            },
            [&] {
                advanceKernel(Exec{}, v, p);
                // Where they live (each reduction waits for the advance). Over ranks they wait
                // in pending_ (summed over the ranks only where read: gatherCounters); the
                // iteration then adds only its rays to stats.
                MltIterationCounts c = buf_.reduceCounters(device());
                if (comm_.size() == 1) return c;
                pending_.add(c);
                return MltIterationCounts{c.rays, 0, 0, 0};
            },
            [&] { splat(buf_.batch, buf_.image.data()); }, [&] { sortChains(); });
        // Bounds the pending sums; every rank reaches the same count after the same iteration.
        if (pending_.iterations() >= kMltMostPendingIterations) gatherCounters();
        return rays;
    }

    void gatherCounters() override {
        if (comm_.size() > 1) pending_.gather(comm_, stats, b_);
    }

    /// Collective over the ranks: their splat sums are summed (in rank order) into the image.
    Image develop() override { return film_.develop(splatSums().data(), b_, splatWeight()); }
    Image developSums(const std::vector<double>& sums, double weight) const override {
        return film_.develop(sums.data(), b_, weight);
    }
    std::vector<double> splatSums() override {
        gatherCounters();  // collective like the film sum below; develop's b is the whole render's
        const uint64_t pending = buf_.pendingIterations(stats.iterations);
        std::vector<double> sums = buf_.image.toHost();
        if (pending > 0) {
            // The unfinished batch goes into a copy of the sums; the render's own stay as they are.
            Buffer<double> copy(device(), sums);
            splat(pending, copy.data());
            sums = copy.toHost();
        }
        if (comm_.size() > 1) comm_.sum(std::span<double>(sums));
        return sums;
    }

    // Checkpoints hold the chain-major store: a dimension-major one is transposed on the host
    // (mlt_checkpoint.h), so a checkpoint resumes on either device.
    // Over ranks (collective): every rank's part goes to rank 0, which writes the whole render
    // (mlt_rank_checkpoint.h); the other ranks write nothing. A resume reads the whole render
    // on every rank, which keeps its own part. The caller gathers the counters first
    // (MltRenderer::save), so that the file holds the whole render's b and counters.
    void save(std::ostream& out) const override {
        MltCheckpoint c = mltCheckpointOf(stats, b_, buf_);
        c.pixelWeight = pixelWeight_.toHost();
        if constexpr (kCompact) {
            c.fine = toChainMajor(fine_.toHost(), slots_[0], 3);
            c.coarse = toChainMajor(coarse_.toHost(), slots_[1], 1);
        } else {
            c.values = toChainMajor(values_.toHost(), slots_[0], 1);
        }
        if (comm_.size() == 1) return writeMltCheckpoint(out, checkpointKeys(), c);
        std::ostringstream part;
        writeMltCheckpoint(part, checkpointKeys(), c);
        const std::string bytes = part.str();
        const std::vector<std::vector<uint8_t>> parts =
            comm_.allGather(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
        if (!comm_.isRoot()) return;
        std::vector<MltCheckpoint> read;
        for (int q = 0; q < comm_.size(); ++q) {
            std::istringstream in(std::string(parts[size_t(q)].begin(), parts[size_t(q)].end()));
            const uint64_t chains = mltShareOf(settings.chains, q, comm_.size()).count;
            read.push_back(readMltCheckpoint(in, checkpointKeys(), checkpointSizes(chains, 1), stats));
        }
        writeMltCheckpoint(out, checkpointKeys(), mergeMltCheckpoints(read, chainWidths()));
    }

    void load(std::istream& in) override {
        const MltCheckpointSizes sizes = checkpointSizes(settings.chains, size_t(comm_.size()));
        MltCheckpoint c = readMltCheckpoint(in, checkpointKeys(), sizes, stats);  // throws before any change
        if (comm_.size() > 1)
            c = mltCheckpointPart(c, chainWidths(), MltShare{chainFirst(), localChains_}, settings.chains,
                                  comm_.rank(), comm_.size());
        restoreMltCheckpoint(c, stats, b_, buf_);
        pending_.clear();
        if constexpr (kCompact) {
            fine_.copyFromHost(fromChainMajor(c.fine, slots_[0], 3));
            coarse_.copyFromHost(fromChainMajor(c.coarse, slots_[1], 1));
        } else {
            values_.copyFromHost(fromChainMajor(c.values, slots_[0], 1));
        }
        setPixelWeight(c.pixelWeight);
        started = true;
    }

private:
    static Device device() { return Exec::device(); }

    /// Waits for the device, then the seconds since t (a GPU's launches are asynchronous).
    static double secondsSince(MltClock::time_point t) {
        detail::synchronizeOn(device());
        return std::chrono::duration<double>(MltClock::now() - t).count();
    }

    template <class T>
    std::vector<T> toChainMajor(const std::vector<T>& stored, size_t slots, size_t width) const {
        return kDimensionMajor ? mltTransposeCells(stored, slots, localChains_, width) : stored;
    }
    template <class T>
    std::vector<T> fromChainMajor(const std::vector<T>& chainMajor, size_t slots, size_t width) const {
        return kDimensionMajor ? mltTransposeCells(chainMajor, localChains_, slots, width) : chainMajor;
    }

    /// Elements per chain of the chain store's arrays (0: a placeholder, mlt_rank_checkpoint.h).
    MltChainWidths chainWidths() const {
        MltChainWidths w;
        if constexpr (kCompact) {
            w.fine = 3 * slots_[0];
            w.coarse = slots_[1];
        } else {
            w.values = slots_[0];
        }
        w.splats = size_t(settings.proposals) + 1;
        return w;
    }

    /// A checkpoint's array sizes for `chains` chains and `films` splat-sum films (this rank's
    /// part: localChains() and 1; the whole render: settings.chains and the rank count).
    MltCheckpointSizes checkpointSizes(uint64_t chains, size_t films) const {
        const MltChainWidths w = chainWidths();
        MltCheckpointSizes sizes = mltCheckpointSizes(settings, pixels_, buf_, 0, 0, 0);
        auto store = [&](size_t width, bool has) { return has ? std::max<size_t>(1, width * chains) : 0; };
        sizes.fine = store(w.fine, kCompact);
        sizes.coarse = store(w.coarse, kCompact);
        sizes.values = store(w.values, !kCompact);
        sizes.chains = chains;
        sizes.image *= films;
        sizes.splatsPerIteration = chains * w.splats;
        return sizes;
    }

    /// The relative target's pixel weights, where the kernels read them (params_.pixelWeight).
    void setPixelWeight(const std::vector<float>& weights) {
        pixelWeight_ = weights.empty() ? Buffer<float>() : Buffer<float>(device(), weights);
        params_.pixelWeight = pixelWeight_.empty() ? nullptr : pixelWeight_.data();
    }

    MltCheckpointKeys checkpointKeys() const {
        return mltCheckpointKeys(params_, settings, store_.dims, film_.filter());
    }

    void bindStore() {
        if constexpr (kCompact) {
            store_.fine = fine_.data();
            store_.coarse = coarse_.data();
        } else {
            store_.values = values_.data();
        }
    }

    MltChainView<Store> view() { return buf_.view(store_); }

    /// Adds the splats of the first `iterations` slots to `target` (kMltValuesPerPixel sums per
    /// pixel, the device's memory).
    void splat(uint64_t iterations, double* target) {
        using namespace mlt_driver_detail;
        const MltSplatView v = buf_.splatView(film_, params_.width, params_.height, iterations, target);
        if (settings.splat == MltSplatKind::Atomic) {
            splatAtomicKernels(Exec{}, v, pixels_);
            return;
        }
        splatKeyKernel(Exec{}, v, buf_.sortKeys.data(), buf_.sortValues.data());
        radixSortPairs(device(), Span<uint32_t>(buf_.sortKeys.data(), v.count),
                       Span<uint32_t>(buf_.sortValues.data(), v.count), 32);
        splatGatherKernels(Exec{}, v, buf_.pixelStart.data(), pixels_);
    }

    /// Reorders the chains by the Morton code of their film position and first-bounce direction
    /// samples (a stable radix sort of (key, chain)), so that neighbouring work items trace
    /// similar paths; every per-chain array is permuted into the sorted order.
    void sortChains() {
        mlt_driver_detail::mortonKernel(Exec{}, view(), params_.width, params_.height, mortonKeys_.data(),
                                        order_.data());
        radixSortPairs(device(), mortonKeys_.span(), order_.span(), 64);
        permuteInPlace(buf_.pos.data(), sizeof(Vec2f), 1, 1);
        permuteInPlace(buf_.value.data(), sizeof(Spectrum), 1, 1);
        permuteInPlace(buf_.importance.data(), sizeof(float), 1, 1);
        permuteInPlace(buf_.usedDims.data(), sizeof(uint16_t), 1, 1);
        if constexpr (kCompact) {
            permuteInPlace(fine_.data(), 3, slots_[0], store_.fineChainStride);
            permuteInPlace(coarse_.data(), sizeof(uint16_t), slots_[1], store_.coarseChainStride);
        } else {
            permuteInPlace(values_.data(), sizeof(float), slots_[0], store_.chainStride);
        }
    }
    /// Permutes `rows` rows of per-chain elements (element (row, c) at row * rowStride + c *
    /// chainStride) in place, through the scratch array.
    void permuteInPlace(void* data, size_t elementBytes, size_t rows, size_t chainStride) {
        if (rows == 0) return;
        const uint32_t n = localChains_;
        const size_t rowStride = chainStride == 1 ? n : 1;
        mlt_driver_detail::permute(Exec{}, data, permuteScratch_.data(), elementBytes, n, rows, rowStride,
                                   chainStride, order_.data());
        detail::copyOn(device(), data, permuteScratch_.data(), elementBytes * rows * n);
    }
    /// The largest per-chain array, in bytes: the permutation's scratch.
    size_t permuteScratchBytes(uint32_t bounces) const {
        const size_t n = localChains_;
        if constexpr (kCompact) return mltGpuPermuteScratchBytes(localChains_, bounces);
        return std::max({sizeof(float) * slots_[0] * n, sizeof(Spectrum) * n, sizeof(Vec2f) * n});
    }

    DeviceScene scene_;
    MltFilm film_;
    MltChainBuffers buf_;
    Store store_;
    size_t slots_[2] = {0, 0};  // per chain: fine and coarse slots (compact), or coordinates (float)
    Buffer<uint8_t> fine_, permuteScratch_;
    Buffer<uint16_t> coarse_;
    Buffer<float> values_;
    Buffer<float> pixelWeight_;
    Buffer<uint32_t> order_;
    Buffer<uint64_t> mortonKeys_;
    MltNormalisation b_;
    MltPendingCounts pending_;  // over ranks: this rank's counters since the last gatherCounters()
};

}  // namespace caustica
