#include "caustica/integrators/mlt/mlt_integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <istream>
#include <optional>
#include <ostream>
#include <vector>

#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_bootstrap.h"
#include "caustica/integrators/mlt/mlt_buffers.h"
#include "caustica/integrators/mlt/mlt_checkpoint.h"
#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/integrators/mlt/mlt_kernel.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/device.h"
#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"

namespace caustica {

MltStateKind parseMltStateKind(const std::string& name) {
    if (name == "compact") return MltStateKind::Compact;
    if (name == "float") return MltStateKind::Float;
    throw Error("unknown MLT state '" + name + "' (use compact or float)");
}
MltSplatKind parseMltSplatKind(const std::string& name) {
    if (name == "atomic") return MltSplatKind::Atomic;
    if (name == "sort") return MltSplatKind::Sort;
    throw Error("unknown MLT splat mode '" + name + "' (use atomic or sort)");
}
MltStart parseMltStart(const std::string& name) {
    if (name == "bootstrap") return MltStart::Bootstrap;
    if (name == "uniform") return MltStart::Uniform;
    throw Error("unknown MLT start '" + name + "' (use bootstrap or uniform)");
}

uint32_t mltStoredBounces(const PathSettings& settings) {
    if (settings.maxDepth < 0) return kMltUnboundedStoredBounces;
    return std::min<uint32_t>(uint32_t(std::max(settings.maxDepth - 1, 0)), kMltMaxStoredBounces);
}

uint32_t mltDefaultChains(bool gpu, uint64_t pixels) {
    if (!gpu) return kMltDefaultChains;
    return uint32_t(std::clamp<uint64_t>(pixels / 2, 4096, uint64_t(1) << 19));
}

uint32_t mltCheckpointChains(std::istream& in) {
    // Only the keys' order matters here: the values are the file's.
    const MltCheckpointKeys keys =
        mltCheckpointKeys(MltStepParams{}, MltSettings{}, 0, Filter::fromDesc(FilterDesc{}));
    const std::optional<uint64_t> chains = peekMltCheckpointKey(in, keys, "chains");
    return chains && *chains >= 1 && *chains <= kMltMaxChains ? uint32_t(*chains) : 0;
}

uint64_t mltDefaultBootstrapSamples(uint32_t chains, uint64_t pixels) {
    return std::max<uint64_t>(uint64_t(4) * chains, std::min<uint64_t>(64 * pixels, uint64_t(1) << 24));
}

size_t mltBytesPerChain(MltStateKind kind, uint32_t storedBounces) {
    const size_t samples = kind == MltStateKind::Compact ? CompactChainStore::bytesPerDims(storedBounces)
                                                         : FloatChainStore::bytesPerDims(storedBounces);
    return samples + sizeof(Vec2f) + sizeof(Spectrum) + sizeof(float) + sizeof(uint16_t);
}

void validateMltSettings(const MltSettings& s) {
    if (s.chains == 0) throw Error("MLT needs at least one chain");
    if (s.proposals == 0 || s.proposals > 64) throw Error("MLT proposals per step must be in 1..64");
    if (!(s.largeStepProbability >= 0 && s.largeStepProbability <= 1))
        throw Error("MLT large-step probability must be in [0, 1]");
    if (!(s.mutation.s1 > 0 && s.mutation.s2 >= s.mutation.s1 && s.mutation.s2 < 1))
        throw Error("MLT small-step sizes must satisfy 0 < s1 <= s2 < 1");
    if (uint64_t(std::max<uint32_t>(s.splatBatch, 1)) * s.chains * (uint64_t(s.proposals) + 1) > 0xffffffffull)
        throw Error("MLT: a splat batch (iterations x chains x (proposals + 1)) must stay below 2^32 splats");
}

MltStepParams mltStepParams(const Scene& scene, const PathSettings& path, const MltSettings& s, uint64_t seed) {
    MltStepParams p;
    p.seed = seed;
    p.proposals = s.proposals;
    p.largeStepProbability = s.largeStepProbability;
    p.mutation = s.mutation;
    p.path = path;
    p.width = scene.film.width;
    p.height = scene.film.height;
    return p;
}

MltRenderer::Impl::Impl(const Scene& scene, const PathSettings& path, const MltSettings& s, uint64_t seed)
    : settings(s), params_(mltStepParams(scene, path, s, seed)) {
    validateMltSettings(s);
    pixels_ = uint32_t(params_.width) * uint32_t(params_.height);
}

uint64_t mltBootstrapCount(const MltSettings& s, uint32_t pixels) {
    return s.bootstrapSamples > 0 ? s.bootstrapSamples : mltDefaultBootstrapSamples(s.chains, pixels);
}

std::vector<uint64_t> mltChainStarts(const float* importance, uint64_t m, uint32_t n, MltStart start,
                                     uint64_t seed) {
    std::vector<uint64_t> starts(n);
    if (start == MltStart::Uniform) {
        for (uint32_t c = 0; c < n; ++c) starts[c] = c % m;  // ordinary samples, I may be 0
        return starts;
    }
    std::vector<double> cdf(m);
    double acc = 0;
    for (uint64_t i = 0; i < m; ++i) cdf[i] = (acc += double(importance[i]));
    const double offset = double(uniformFloat(mix64(mltBootstrapKey(seed, ~uint64_t(0)))));
    for (uint32_t c = 0; c < n; ++c) {
        const double target = (double(c) + offset) / double(n) * acc;
        const auto it = std::upper_bound(cdf.begin(), cdf.end(), target);
        starts[c] = std::min<uint64_t>(uint64_t(it - cdf.begin()), m - 1);
    }
    return starts;
}

namespace {

/// Fraction of a filter's integral that falls inside [0, size) around each pixel centre, one
/// axis: the splat sums of border pixels are divided by it (the path tracer's film normalises by
/// the weights of the samples it has, which amounts to the same).
std::vector<double> borderCoverage(const Filter& filter, int size) {
    std::vector<double> coverage(size_t(size), 1.0);
    const double integral = filter.integral(), r = filter.radius;
    constexpr int kSteps = 4096;
    for (int x = 0; x < size; ++x) {
        const double c = x + 0.5;
        if (c - r >= 0 && c + r <= size) continue;
        const double lo = std::max(0.0, c - r), hi = std::min(double(size), c + r), h = (hi - lo) / kSteps;
        double sum = 0;
        for (int i = 0; i < kSteps; ++i) sum += filter.eval(Float(lo + (i + 0.5) * h - c));
        coverage[size_t(x)] = sum * h / integral;
    }
    return coverage;
}

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

MltFilm::MltFilm(const FilterDesc& filter, int width, int height)
    : filter_(Filter::fromDesc(filter)),
      width_(width),
      height_(height),
      coverageX_(borderCoverage(filter_, width)),
      coverageY_(borderCoverage(filter_, height)) {}

Image MltFilm::develop(const double* sums, const MltNormalisation& b, double totalWeight) const {
    Image out(width_, height_);
    if (totalWeight == 0) return out;
    const double integral = filter_.integral();
    const double scale = double(width_) * double(height_) / totalWeight / (integral * integral);
    const double chainScale = b.chainScale();
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const size_t pixel = size_t(y) * size_t(width_) + size_t(x);
            const double s = scale / (coverageX_[size_t(x)] * coverageY_[size_t(y)]);
            const double* sum = sums + kMltValuesPerPixel * pixel;
            for (int c = 0; c < 3; ++c) out.rgb[3 * pixel + size_t(c)] = float((sum[c] * chainScale + sum[3 + c]) * s);
        }
    return out;
}

namespace {

template <class Store>
class MltImpl final : public MltRenderer::Impl {
public:
    MltImpl(const Scene& scene, const Accel& accel, const PathSettings& path, const MltSettings& s, uint64_t seed)
        : Impl(scene, path, s, seed),
          scene_(scene),
          accel_(accel),
          device_(Device::cpu()),
          film_(scene.film.filter, scene.film.width, scene.film.height),
          buf_(device_, s.chains, s.proposals, pixels_, s.splat, mltSplatBatch(s, pixels_)) {
        const uint32_t n = s.chains;
        const uint32_t bounces = mltStoredBounces(path);
        allocateStore(n, bounces);
        stats.bytesPerChain = mltBytesPerChain(std::is_same_v<Store, CompactChainStore> ? MltStateKind::Compact
                                                                                         : MltStateKind::Float,
                                               bounces);
        stats.stateBytes = stats.bytesPerChain * n;
        stats.scratchBytes = buf_.scratchBytes();
    }

    void bootstrap() override {
        const auto t0 = Clock::now();
        const uint32_t n = settings.chains;
        const uint64_t m = mltBootstrapCount(settings, pixels_);
        std::vector<float> importance(m);  // host memory: the CPU driver's device
        std::vector<uint32_t> pixel(m);
        Buffer<uint32_t> rays(device_, m);
        float* I = importance.data();
        uint32_t* px = pixel.data();
        uint32_t* r = rays.data();
        MltStepParams p = params_;  // luminances first: pixelWeight is still null
        accel_.visit([&](const auto& intersector) {
            parallelFor(device_, "mlt.bootstrap", m, [&](size_t i) {
                r[i] = 0;
                I[i] = bootstrapImportance<Store>(scene_.view(), intersector, p, i, r[i], px[i]);
            }, 64);
        });
        stats.rays += reduceSum(device_, rays.constSpan());
        const MltBootstrapPlan plan =
            planMltBootstrap(importance, pixel, settings, params_.width, params_.height, params_.seed);
        pixelWeight_ = plan.pixelWeight;
        params_.pixelWeight = pixelWeight_.empty() ? nullptr : pixelWeight_.data();
        p.pixelWeight = params_.pixelWeight;
        adoptMltBootstrap(plan, m, b_, stats);
        const std::vector<uint64_t>& start = plan.starts;
        const MltChainView<Store> v = view();
        Buffer<uint32_t> startRays(device_, n);
        uint32_t* sr = startRays.data();
        accel_.visit([&](const auto& intersector) {
            parallelFor(device_, "mlt.start", n, [&](size_t c) {
                uint32_t r = 0;
                startChain(scene_.view(), intersector, v, p, uint32_t(c), start[c], r);
                sr[c] = r;
            }, 64);
        });
        stats.rays += reduceSum(device_, startRays.constSpan());
        stats.bootstrapSeconds = secondsSince(t0);
        started = true;
    }

    uint64_t iterate() override {
        const uint32_t n = settings.chains, k = settings.proposals;
        MltStepParams p = params_;
        p.iteration = uint32_t(stats.iterations);
        p.b = float(b_.b0);
        const MltChainView<Store> v = buf_.view(store_, stats.iterations);

        return mltTimedIteration(
            stats, b_, settings, buf_.batch, secondsSince,
            [&] {
                accel_.visit([&](const auto& intersector) {
                    parallelFor(device_, "mlt.propose", size_t(n) * k, [&](size_t item) {
                        traceProposal(scene_.view(), intersector, v, p, uint32_t(item));
                    }, 16);
                });
            },
            [&] {
                parallelFor(device_, "mlt.advance", n, [&](size_t c) { advanceChain(v, p, uint32_t(c)); }, 256);
                return buf_.reduceCounters(device_);  // where they live, as on the GPU
            },
            [&] { splat(buf_.batch, buf_.image.data()); }, [&] { sortChains(); });
    }

    Image develop() override {
        const double total = double(settings.chains) * settings.proposals * double(stats.iterations);
        const uint64_t pending = buf_.pendingIterations(stats.iterations);
        if (pending == 0) return film_.develop(buf_.image.data(), b_, total);
        std::vector<double> sums = buf_.image.toHost();
        splat(pending, sums.data());
        return film_.develop(sums.data(), b_, total);
    }

    void save(std::ostream& out) const override {
        MltCheckpoint c = mltCheckpointOf(stats, b_, buf_);
        c.pixelWeight = pixelWeight_;
        c.fine = fine_.toHost();  // chain-major already: the checkpoint's layout
        c.coarse = coarse_.toHost();
        c.values = values_.toHost();
        writeMltCheckpoint(out, checkpointKeys(), c);
    }

    void load(std::istream& in) override {
        const MltCheckpointSizes sizes =
            mltCheckpointSizes(settings, pixels_, buf_, fine_.size(), coarse_.size(), values_.size());
        const MltCheckpoint c = readMltCheckpoint(in, checkpointKeys(), sizes, stats);  // throws before any change
        restoreMltCheckpoint(c, stats, b_, buf_);
        fine_.copyFromHost(c.fine);
        coarse_.copyFromHost(c.coarse);
        values_.copyFromHost(c.values);
        pixelWeight_ = c.pixelWeight;
        params_.pixelWeight = pixelWeight_.empty() ? nullptr : pixelWeight_.data();
        started = true;
    }

private:
    MltCheckpointKeys checkpointKeys() const {
        return mltCheckpointKeys(params_, settings, store_.dims, film_.filter());
    }

    void allocateStore(uint32_t n, uint32_t bounces) {
        const uint32_t dims = mltStoredDims(bounces);
        store_.dims = dims;
        if constexpr (std::is_same_v<Store, CompactChainStore>) {
            const size_t fineSlots = kMltCameraDims + 4 * size_t(bounces), coarseSlots = 3 * size_t(bounces);
            fine_ = Buffer<uint8_t>(device_, std::max<size_t>(1, 3 * fineSlots * n));
            coarse_ = Buffer<uint16_t>(device_, std::max<size_t>(1, coarseSlots * n));
            fine_.zero();  // slots past a chain's path stay unwritten: keep checkpoints reproducible
            coarse_.zero();
            store_.fineChainStride = fineSlots;  // chain-major: a chain's vector is contiguous
            store_.fineDimStride = 1;
            store_.coarseChainStride = coarseSlots;
            store_.coarseDimStride = 1;
        } else {
            values_ = Buffer<float>(device_, size_t(dims) * n);
            values_.zero();
            store_.chainStride = dims;
            store_.dimStride = 1;
        }
        bindStore();
    }
    void bindStore() {
        if constexpr (std::is_same_v<Store, CompactChainStore>) {
            store_.fine = fine_.data();
            store_.coarse = coarse_.data();
        } else {
            store_.values = values_.data();
        }
    }

    MltChainView<Store> view() { return buf_.view(store_); }

    /// Adds the splats of the first `iterations` slots to `target` (kMltValuesPerPixel sums per pixel).
    void splat(uint64_t iterations, double* target) {
        const MltSplatView v = buf_.splatView(film_, params_.width, params_.height, iterations, target);
        if (settings.splat == MltSplatKind::Atomic) {
            parallelFor(device_, "mlt.splat_atomic", v.count, [&](size_t i) { splatAtomic(v, uint32_t(i)); }, 256);
            parallelFor(device_, "mlt.splat_flush", pixels_, [&](size_t p) { flushAtomicPixel(v, uint32_t(p)); }, 256);
            return;
        }
        uint32_t* keys = buf_.sortKeys.data();
        uint32_t* values = buf_.sortValues.data();
        parallelFor(device_, "mlt.splat_keys", v.count, [&](size_t i) {
            keys[i] = splatPixel(v, v.splats[i]);
            values[i] = uint32_t(i);
        }, 256);
        radixSortPairs(device_, Span<uint32_t>(keys, v.count), Span<uint32_t>(values, v.count), 32);
        uint32_t* starts = buf_.pixelStart.data();
        parallelFor(device_, "mlt.splat_starts", size_t(pixels_) + 1, [&](size_t p) {
            findPixelStart(starts, keys, v.count, uint32_t(p));
        }, 256);
        parallelFor(device_, "mlt.splat_gather", pixels_, [&](size_t p) { gatherSplats(v, uint32_t(p)); }, 64);
    }

    /// Reorders the chains by the Morton code of their film position and first-bounce direction
    /// samples, so that neighbouring work items trace similar paths.
    void sortChains() {
        const uint32_t n = settings.chains;
        const MltChainView<Store> v = view();
        Buffer<uint64_t> keys(device_, n);
        Buffer<uint32_t> order(device_, n);
        uint64_t* k = keys.data();
        uint32_t* o = order.data();
        parallelFor(device_, "mlt.morton", n, [&](size_t c) {
            k[c] = mltMortonKey(v, uint32_t(c), params_.width, params_.height);
            o[c] = uint32_t(c);
        }, 256);
        radixSortPairs(device_, keys.span(), order.span(), 64);
        permute(buf_.pos, o);
        permute(buf_.value, o);
        permute(buf_.importance, o);
        permute(buf_.usedDims, o);
        if constexpr (std::is_same_v<Store, CompactChainStore>) {
            permuteRows(fine_, 3 * store_.fineChainStride, o);
            permuteRows(coarse_, store_.coarseChainStride, o);
        } else {
            permuteRows(values_, store_.chainStride, o);
        }
        bindStore();
    }
    template <class T>
    void permute(Buffer<T>& b, const uint32_t* order) { permuteRows(b, 1, order); }
    template <class T>
    void permuteRows(Buffer<T>& b, size_t row, const uint32_t* order) {
        if (row == 0) return;
        Buffer<T> out(device_, b.size());
        const T* src = b.data();
        T* dst = out.data();
        parallelFor(device_, "mlt.permute", settings.chains, [&](size_t c) {
            std::copy(src + size_t(order[c]) * row, src + size_t(order[c] + 1) * row, dst + c * row);
        }, 256);
        b = std::move(out);
    }

    const Scene& scene_;
    const Accel& accel_;
    Device device_;
    MltFilm film_;
    MltChainBuffers buf_;
    Store store_;
    Buffer<uint8_t> fine_;
    Buffer<uint16_t> coarse_;
    Buffer<float> values_;
    MltNormalisation b_;
    std::vector<float> pixelWeight_;  // relative target only (params_.pixelWeight points here)
};

}  // namespace

MltRenderer::MltRenderer(const Scene& scene, const Accel& accel, const PathSettings& path,
                         const MltSettings& settings, uint64_t seed) {
    if (settings.state == MltStateKind::Compact)
        impl_ = std::make_unique<MltImpl<CompactChainStore>>(scene, accel, path, settings, seed);
    else
        impl_ = std::make_unique<MltImpl<FloatChainStore>>(scene, accel, path, settings, seed);
}
MltRenderer::MltRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MltRenderer::~MltRenderer() = default;
void MltRenderer::bootstrap() { impl_->bootstrap(); }
uint64_t MltRenderer::iterate() { return impl_->iterate(); }
Image MltRenderer::develop() const { return impl_->develop(); }
const MltStats& MltRenderer::stats() const { return impl_->stats; }
const MltSettings& MltRenderer::settings() const { return impl_->settings; }
bool MltRenderer::started() const { return impl_->started; }
void MltRenderer::save(std::ostream& out) const { impl_->save(out); }
void MltRenderer::load(std::istream& in) { impl_->load(in); }
double MltRenderer::mutationsPerPixel() const {
    return impl_->pixels() > 0 ? double(impl_->stats.proposals) / double(impl_->pixels()) : 0;
}

}  // namespace caustica
