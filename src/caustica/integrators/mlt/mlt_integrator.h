// mlt_integrator.h — host driver of many-chain primary-sample-space Metropolis light transport
// (mlt_kernel.h): bootstrap by ordinary Monte Carlo, lock-step iterations of all chains, splat
// accumulation, optional Morton sorting of the chains, and the developed image.
//
//     MltRenderer mlt(scene, accel, readPathSettings(params), readMltSettings(params, chains), seed);
//     mlt.bootstrap();                       // b, and chain starts in proportion to luminance
//     while (...) mlt.iterate();             // each chain: k proposals, splats, next state
//     Image image = mlt.develop();
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/film/image.h"
#include "caustica/integrators/mlt/mlt_state.h"
#include "caustica/integrators/mlt/mlt_target.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

enum class MltStateKind { Compact, Float };  // fixed-point 24/16-bit coordinates, or float32
enum class MltSplatKind { Atomic, Sort };
enum class MltStart { Bootstrap, Uniform };  // uniform: chains start at unselected samples (for experiments)

MltStateKind parseMltStateKind(const std::string& name);  // "compact" | "float"
MltSplatKind parseMltSplatKind(const std::string& name);  // "atomic" | "sort"
MltStart parseMltStart(const std::string& name);          // "bootstrap" | "uniform"

/// Default chain count on a CPU. There few long chains beat many short ones at equal time: a chain's
/// error is dominated by its first steps and by chains started at the same bootstrap sample
/// (docs/PERFORMANCE.md).
inline constexpr uint32_t kMltDefaultChains = 1024;
/// Default chain count for `pixels` pixels: kMltDefaultChains on a CPU; on a GPU half a chain per
/// pixel, as the founding paper ran (524,288 chains at 1024x1024; Frolov & Galaktionov 2017,
/// fig. 5), within [4096, 524288]. A GPU needs enough chains to fill its threads, and the paper
/// found 2-4x fewer than that costs little tracing speed (its fig. 3), so small images keep the
/// chains long instead.
uint32_t mltDefaultChains(bool gpu, uint64_t pixels);
/// Most chains a render may have (the command line's bound).
inline constexpr uint32_t kMltMaxChains = uint32_t(1) << 26;
/// The chain count of the MLT checkpoint in `in`, read once the whole file checks out (magic,
/// version, checksum); 0 for a file that does not or a count outside [1, kMltMaxChains]. A resume
/// that sets no chain count takes it: the CPU's and the GPU's defaults differ, and a checkpoint
/// written by either driver resumes on the other.
uint32_t mltCheckpointChains(std::istream& in);
/// Default bootstrap size M: 64 per pixel, at most 2^24, at least 4 per chain. Fewer start the
/// chains at the same bright samples (a sample of importance I starts about chains x I / (M b)
/// chains, which then move together) and blur the relative target's brightness map: on
/// cornell-water 64 per pixel gave 2-4x lower error than 16 at equal mutations (docs/PERFORMANCE.md).
uint64_t mltDefaultBootstrapSamples(uint32_t chains, uint64_t pixels);

struct MltSettings {
    uint32_t chains = kMltDefaultChains;  // chains stepped in lock step
    uint64_t bootstrapSamples = 0;        // M ordinary Monte Carlo samples; 0 = mltDefaultBootstrapSamples
    Float largeStepProbability = 0.1f;
    MltMutation mutation;                 // small-step sizes s1, s2
    uint32_t proposals = 1;               // k proposals per step (split transitions)
    MltStateKind state = MltStateKind::Compact;
    MltSplatKind splat = MltSplatKind::Atomic;
    uint32_t sortEvery = 0;               // Morton-sort the chains every N iterations; 0 = never
    MltStart start = MltStart::Bootstrap;
    MltTarget target = MltTarget::Relative;  // what the chains sample in proportion to (mlt_target.h)
    uint32_t splatBatch = 0;              // iterations per splat pass; 0 = mltSplatBatch's choice
};

/// Bounces whose primary samples a chain stores: max_depth - 1 when bounded (the last segment
/// draws none), else kMltUnboundedStoredBounces; at most kMltMaxStoredBounces. Later bounces use
/// independent numbers.
inline constexpr uint32_t kMltUnboundedStoredBounces = 24;
inline constexpr uint32_t kMltMaxStoredBounces = 64;
uint32_t mltStoredBounces(const PathSettings& settings);
/// Bytes of persistent state per chain (primary samples plus film position, F, I and U).
size_t mltBytesPerChain(MltStateKind kind, uint32_t storedBounces);

struct MltStats {
    double b = 0;                   // normalisation: mean luminance of the path-space integrand
    uint64_t bootstrapSamples = 0, largeSteps = 0;
    uint64_t iterations = 0;
    uint64_t proposals = 0;         // paths traced by the chains (k per chain and iteration)
    uint64_t accepted = 0;          // chain moves
    uint64_t rays = 0;              // all rays, bootstrap included
    size_t bytesPerChain = 0, stateBytes = 0, scratchBytes = 0;
    double bootstrapSeconds = 0, traceSeconds = 0, advanceSeconds = 0, splatSeconds = 0, sortSeconds = 0;
};

class MltRenderer {
public:
    MltRenderer(const Scene& scene, const Accel& accel, const PathSettings& path, const MltSettings& settings,
                uint64_t seed);
    /// The CPU's driver (above), or any device's from makeMltDriver (mlt_driver.h); mlt_impl.h defines Impl.
    struct Impl;
    explicit MltRenderer(std::unique_ptr<Impl> impl);
    ~MltRenderer();
    MltRenderer(const MltRenderer&) = delete;
    MltRenderer& operator=(const MltRenderer&) = delete;

    /// Traces the bootstrap samples, estimates b and starts every chain. Throws caustica::Error
    /// when no bootstrap sample carries light (b = 0: the image is black).
    void bootstrap();
    /// One iteration of every chain. Returns the rays traced.
    uint64_t iterate();
    /// The image so far (the splats of an unfinished batch included, without adding them to the
    /// splat sums): splat sums scaled by pixels / total chain splat weight, divided by the
    /// filter's integral (and its coverage at the image border). Over ranks it is collective:
    /// every rank's splat sums are summed, and every rank gets the image.
    Image develop() const;
    /// The image of the iterations since develop's state `since` alone (their splats, scaled by
    /// their own splat weight, with the current b), and `since` moved to now: the batch estimate
    /// of the variance AOV (render/aov_session.h). An empty `since` starts it (a black image).
    /// Collective over ranks, as develop().
    struct SplatState {
        std::vector<double> sums;
        double weight = 0;
    };
    Image developSince(SplatState& since) const;
    /// True once bootstrap() ran or a checkpoint was loaded.
    bool started() const;
    /// Resumable checkpoints: save() writes the whole state (chains, splat sums, b, counters);
    /// load() restores it into a renderer built with the same scene and settings, in place of
    /// bootstrap(), and throws caustica::Error naming what differs (a damaged or foreign file
    /// leaves the renderer untouched). Every driver (CPU and GPU) has them.
    void save(std::ostream& out) const;
    void load(std::istream& in);
    /// Over ranks, collective: brings stats() up to the whole render's (the ranks sum their
    /// counters only where they are read: develop, save and here). Nothing in one process.
    void gatherCounters();
    /// Proposals per pixel so far (the analogue of samples per pixel), of the whole render.
    double mutationsPerPixel() const;
    /// The chains this rank steps (all of settings().chains in one process; makeMltDriver's
    /// `comm` splits them over ranks).
    uint32_t localChains() const;
    const MltStats& stats() const;
    const MltSettings& settings() const;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace caustica
