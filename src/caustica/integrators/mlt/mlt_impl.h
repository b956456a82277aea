// mlt_impl.h — what every MLT driver shares (the CPU's in mlt_integrator.cpp, a GPU's in cuda/):
// the interface behind MltRenderer and the host-side steps that do not depend on where the
// chains live — settings checks, kernel parameters, the choice of the chains' starts, the
// estimate of b and the developed image. Drivers include it; users of MltRenderer do not.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "caustica/film/filter.h"
#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/mlt/mlt_kernel.h"

namespace caustica {

struct MltRenderer::Impl {
    virtual ~Impl() = default;
    virtual void bootstrap() = 0;
    virtual uint64_t iterate() = 0;
    virtual Image develop() const = 0;
    /// Resumable checkpoints: a driver that can write and restore its whole state overrides all
    /// three; the defaults say it cannot (save/load throw caustica::Error).
    virtual bool resumable() const { return false; }
    virtual void save(std::ostream& out) const;
    virtual void load(std::istream& in);
    MltStats stats;
    MltSettings settings;
    uint32_t pixels = 0;
    bool started = false;  // bootstrapped, or loaded from a checkpoint
};

/// Throws caustica::Error (one line) for settings no driver can run.
void validateMltSettings(const MltSettings& settings);
/// `settings`, validated (for constructors' initialiser lists).
inline const MltSettings& validatedMltSettings(const MltSettings& settings) {
    validateMltSettings(settings);
    return settings;
}
/// Kernel parameters of a render of `scene`; the driver sets iteration, b and pixelWeight.
MltStepParams mltStepParams(const Scene& scene, const PathSettings& path, const MltSettings& settings,
                            uint64_t seed);
/// M: settings.bootstrapSamples, or the default for the chain count and image size.
uint64_t mltBootstrapCount(const MltSettings& settings, uint32_t pixels);

/// The bootstrap sample each chain starts at: in proportion to importance (inclusive prefix sum
/// and a stratified binary search, one random offset for all, chains evenly spaced) or, for
/// MltStart::Uniform, sample c for chain c. `importance` holds the M bootstrap importances.
std::vector<uint64_t> mltChainStarts(const float* importance, uint64_t count, uint32_t chains, MltStart start,
                                     uint64_t seed);

/// Running estimate of b = E[I]: the bootstrap mean, refined by every large step's I.
struct MltNormalisation {
    double sum = 0, count = 0;
    void add(double importanceSum, double samples) {
        sum += importanceSum;
        count += samples;
    }
    double b() const { return count > 0 ? sum / count : 0; }
};

/// Turns the splat sums (3 doubles per pixel, all iterations) into the image: scaled by pixels /
/// total chain splat weight, divided by the filter's integral squared (the splat and the
/// density of positions) and by the filter's coverage at the image border.
class MltFilm {
public:
    MltFilm(const FilterDesc& filter, int width, int height);
    Image develop(const double* sums, double totalWeight) const;
    const Filter& filter() const { return filter_; }

private:
    Filter filter_;
    int width_, height_;
    std::vector<double> coverageX_, coverageY_;
};

}  // namespace caustica
