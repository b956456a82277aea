#include "caustica/integrators/mlt/mlt_integrator.h"

#include <algorithm>
#include <cmath>
#include <istream>
#include <optional>
#include <string>
#include <ostream>
#include <vector>

#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_bootstrap.h"
#include "caustica/integrators/mlt/mlt_checkpoint.h"
#include "caustica/integrators/mlt/mlt_driver.h"
#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/integrators/mlt/mlt_kernel.h"
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

MltShare mltShareOf(uint64_t total, int rank, int ranks) {
    const uint64_t first = total * uint64_t(rank) / uint64_t(ranks);
    return MltShare{first, total * uint64_t(rank + 1) / uint64_t(ranks) - first};
}

MltRenderer::Impl::Impl(const Scene& scene, const PathSettings& path, const MltSettings& s, uint64_t seed,
                        Communicator& comm)
    : settings(s), comm_(comm), params_(mltStepParams(scene, path, s, seed)) {
    validateMltSettings(s);
    if (s.chains < uint32_t(comm.size()))
        throw Error("MLT: " + std::to_string(s.chains) + " chains cannot be split over " +
                    std::to_string(comm.size()) + " ranks (at least one chain per rank; --mlt-chains)");
    pixels_ = uint32_t(params_.width) * uint32_t(params_.height);
    const MltShare share = mltShareOf(s.chains, comm.rank(), comm.size());
    params_.chainOffset = uint32_t(share.first);
    localChains_ = uint32_t(share.count);
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

}  // namespace

/// borderCoverage of the columns; on a stereo film each eye's, side by side.
static std::vector<double> columnCoverage(const Filter& filter, int width, int eyeWidth) {
    if (eyeWidth <= 0) return borderCoverage(filter, width);
    std::vector<double> eye = borderCoverage(filter, eyeWidth), both = eye;
    both.insert(both.end(), eye.begin(), eye.end());
    return both;
}

MltFilm::MltFilm(const FilterDesc& filter, int width, int height, int eyeWidth)
    : filter_(Filter::fromDesc(filter)),
      width_(width),
      height_(height),
      eyeWidth_(eyeWidth),
      coverageX_(columnCoverage(filter_, width, eyeWidth)),
      coverageY_(borderCoverage(filter_, height)) {
    if (eyeWidth != 0 && 2 * eyeWidth != width) throw Error("mlt: the eye width is not half the film width");
}

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

MltRenderer::MltRenderer(const Scene& scene, const Accel& accel, const PathSettings& path,
                         const MltSettings& settings, uint64_t seed) {
    impl_ = makeMltDriver<CpuExec>(scene, accel, path, settings, seed);
}
MltRenderer::MltRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MltRenderer::~MltRenderer() = default;
void MltRenderer::bootstrap() { impl_->bootstrap(); }
uint64_t MltRenderer::iterate() { return impl_->iterate(); }
Image MltRenderer::develop() const { return impl_->develop(); }
Image MltRenderer::developSince(SplatState& since) const {
    SplatState now{impl_->splatSums(), impl_->splatWeight()};
    if (since.sums.size() != now.sums.size()) since = SplatState{std::vector<double>(now.sums.size(), 0.0), 0.0};
    std::vector<double> delta(now.sums.size());
    for (size_t i = 0; i < delta.size(); ++i) delta[i] = now.sums[i] - since.sums[i];
    const double weight = now.weight - since.weight;
    since = std::move(now);
    return impl_->developSums(delta, weight);
}
const MltStats& MltRenderer::stats() const { return impl_->stats; }
const MltSettings& MltRenderer::settings() const { return impl_->settings; }
bool MltRenderer::started() const { return impl_->started; }
void MltRenderer::save(std::ostream& out) const {
    impl_->gatherCounters();  // the file holds the whole render's counters and b
    impl_->save(out);
}
void MltRenderer::gatherCounters() { impl_->gatherCounters(); }
void MltRenderer::load(std::istream& in) { impl_->load(in); }
uint32_t MltRenderer::localChains() const { return impl_->localChains(); }
double MltRenderer::mutationsPerPixel() const {
    return impl_->pixels() > 0 ? double(impl_->stats.proposals) / double(impl_->pixels()) : 0;
}

}  // namespace caustica
