// mlt_impl.h — what every MLT driver shares (mlt_driver.h, one per device):
// the interface behind MltRenderer and the host-side steps that do not depend on where the
// chains live — settings checks, kernel parameters, the choice of the chains' starts, the
// estimate of b and the developed image. Drivers include it; users of MltRenderer do not.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "caustica/distributed/communicator.h"
#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/mlt/mlt_kernel.h"

namespace caustica {

/// Throws caustica::Error (one line) for settings no driver can run.
void validateMltSettings(const MltSettings& settings);
/// Kernel parameters of a render of `scene`; the driver sets iteration, b and pixelWeight.
MltStepParams mltStepParams(const Scene& scene, const PathSettings& path, const MltSettings& settings,
                            uint64_t seed);

/// The part [first, first + count) of `total` items that rank `rank` of `ranks` takes (contiguous,
/// in rank order, sizes differing by at most one).
struct MltShare {
    uint64_t first = 0, count = 0;
};
MltShare mltShareOf(uint64_t total, int rank, int ranks);

struct MltRenderer::Impl {
    /// Validates `settings` (caustica::Error before a driver allocates anything) and fills what
    /// every driver needs: settings, the kernel parameters, the pixel count and this rank's
    /// chains (settings.chains is the total over the ranks of `comm`).
    Impl(const Scene& scene, const PathSettings& path, const MltSettings& settings, uint64_t seed,
         Communicator& comm = singleProcess());
    virtual ~Impl() = default;
    virtual void bootstrap() = 0;
    virtual uint64_t iterate() = 0;
    /// Not const: the splats of an unfinished batch go through the splat scratch buffers into a
    /// copy of the splat sums; the render's state is left as it was.
    virtual Image develop() = 0;
    /// The splat sums of the iterations so far (kMltValuesPerPixel doubles per pixel; an
    /// unfinished batch's splats included, as develop() takes them). Collective over the ranks
    /// (summed in rank order).
    virtual std::vector<double> splatSums() = 0;
    /// develop() of given splat sums of total chain splat weight `weight`, with the current b:
    /// the image of some iterations' splats alone (the variance AOV's batches, docs/AOV.md).
    virtual Image developSums(const std::vector<double>& sums, double weight) const = 0;
    /// Total chain splat weight of the iterations so far (develop()'s normaliser).
    double splatWeight() const { return double(settings.chains) * settings.proposals * double(stats.iterations); }
    /// Collective over ranks: sums the counters every rank kept since the last call into stats
    /// and b (mlt_ranks.h MltPendingCounts); nothing in one process. splatSums() (so develop)
    /// calls it; MltRenderer calls it before save() and for the statistics.
    virtual void gatherCounters() = 0;
    /// Resumable checkpoints (mlt_checkpoint.h): the whole state, written and restored.
    virtual void save(std::ostream& out) const = 0;
    virtual void load(std::istream& in) = 0;
    uint32_t pixels() const { return pixels_; }
    /// This rank's chains: global indices [chainFirst(), chainFirst() + localChains()).
    uint32_t chainFirst() const { return params_.chainOffset; }
    uint32_t localChains() const { return localChains_; }
    /// stats: counters and b of the whole render on every rank as of the last gatherCounters()
    /// (iterations and proposals: always), except rays (this rank's) and the timings (this rank's).
    MltStats stats;
    MltSettings settings;  // chains: the total over the ranks
    bool started = false;  // bootstrapped, or loaded from a checkpoint

protected:
    Communicator& comm_;
    uint32_t localChains_ = 0;
    MltStepParams params_;  // iteration and b are set per launch, pixelWeight by the bootstrap
    uint32_t pixels_ = 0;
};

/// M: settings.bootstrapSamples, or the default for the chain count and image size.
uint64_t mltBootstrapCount(const MltSettings& settings, uint32_t pixels);

/// The bootstrap sample each chain starts at: in proportion to importance (inclusive prefix sum
/// and a stratified binary search, one random offset for all, chains evenly spaced) or, for
/// MltStart::Uniform, sample c for chain c. `importance` holds the M bootstrap importances.
std::vector<uint64_t> mltChainStarts(const float* importance, uint64_t count, uint32_t chains, MltStart start,
                                     uint64_t seed);

/// Running estimate of b = E[I]: the bootstrap mean, refined by every large step's I.
/// b0, the bootstrap's estimate, stays fixed in the splat weights; the chain layer of the splat
/// sums is scaled by b / b0 when the image is developed (mlt_kernel.h).
struct MltNormalisation {
    double sum = 0, count = 0;
    double b0 = 0;
    void add(double importanceSum, double samples) {
        sum += importanceSum;
        count += samples;
    }
    double b() const { return count > 0 ? sum / count : 0; }
    /// Factor of the chain layer: b / b0 (1 before the bootstrap).
    double chainScale() const { return b0 > 0 ? b() / b0 : 1; }
};

/// Turns the splat sums (kMltValuesPerPixel doubles per pixel, all iterations) into the image:
/// the chain layer times b.chainScale() plus the large-step layer, scaled by pixels / total chain
/// splat weight, divided by the filter's integral squared (the splat and the density of
/// positions) and by the filter's coverage at the image border.
class MltFilm {
public:
    /// eyeWidth > 0: a stereo film, whose seam is a border like the image's (eye_seam.h).
    MltFilm(const FilterDesc& filter, int width, int height, int eyeWidth = 0);
    Image develop(const double* sums, const MltNormalisation& b, double totalWeight) const;
    const Filter& filter() const { return filter_; }
    int eyeWidth() const { return eyeWidth_; }

private:
    Filter filter_;
    int width_, height_, eyeWidth_;
    std::vector<double> coverageX_, coverageY_;
};

}  // namespace caustica
