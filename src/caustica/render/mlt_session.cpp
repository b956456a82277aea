// mlt_session.cpp — the session of Metropolis light transport: a bootstrap step, then one
// lock-step iteration of every chain per step; the checkpoint payload is the MLT state
// (integrators/mlt/mlt_checkpoint.h).
//
// Over ranks (SessionContext::comm; docs/MPI.md): the bootstrap samples are split by
// global index and gathered, so b and the chain starts are one process's; each rank steps the
// chains of its share of the global chain indices (their streams keyed by them); a step runs
// several iterations (mltIterationsPerRankStep), and the iteration counters are summed over the
// ranks only where they are read (develop, save, statistics: b and the counters are then the
// whole render's on every rank, to the bit as if summed every iteration); develop() is
// COLLECTIVE (the splat films are summed over the ranks); save() gathers every rank's chains to
// rank 0, which writes the whole render.
#include <cstdio>
#include <memory>
#include <string>

#include "caustica/integrators/mlt/mlt_driver.h"
#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/mlt/mlt_ranks.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/mlt/mlt_settings.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica {
namespace {

/// The chain count a resume takes from its checkpoint when none is set (the CPU's and the GPU's
/// defaults differ, and a checkpoint written on either resumes on the other); 0 when none.
uint32_t savedChains(const RenderIdentity* saved) {
    if (!saved) return 0;
    for (const IdentityEntry& e : *saved)
        if (e.name == "chains") return uint32_t(std::strtoul(e.value.c_str(), nullptr, 10));
    return 0;
}

const char* stateName(MltStateKind k) { return k == MltStateKind::Compact ? "compact" : "float"; }
const char* targetName(MltTarget t) { return t == MltTarget::Relative ? "relative" : "luminance"; }
const char* splatName(MltSplatKind k) { return k == MltSplatKind::Atomic ? "atomic" : "sort"; }

RenderIdentity mltIdentity(const PathSettings& path, const MltSettings& s) {
    return {identityEntry("max_depth", std::to_string(path.maxDepth)),
            identityEntry("rr_depth", std::to_string(path.rrDepth)),
            identityEntry("hide_emitters", path.hideEmitters ? "true" : "false"),
            identityEntry("chains", std::to_string(s.chains)),
            identityEntry("luminance_samples", std::to_string(s.bootstrapSamples)),
            identityEntry("p_large", identityNumber(s.largeStepProbability)),
            identityEntry("proposals", std::to_string(s.proposals)),
            identityEntry("s1", identityNumber(s.mutation.s1)),
            identityEntry("s2", identityNumber(s.mutation.s2)),
            identityEntry("state", stateName(s.state)),
            identityEntry("target", targetName(s.target)),
            identityEntry("start", s.start == MltStart::Bootstrap ? "bootstrap" : "uniform"),
            identityEntry("sort_every", std::to_string(s.sortEvery))};
}

class MltSession final : public IntegratorSession {
public:
    MltSession(const SessionContext& c, const PathSettings& path, const MltSettings& settings)
        : path_(path), device_(c.device), comm_(c.comm) {
        mlt_ = std::make_unique<MltRenderer>(onDevice(c.device, [&](auto exec) {
            return makeMltDriver<decltype(exec)>(c.scene, c.accel, path_, settings, c.seed, c.comm);
        }));
    }

    /// The bootstrap, or one iteration (one process) or mltIterationsPerRankStep() iterations
    /// (several ranks; fewer where `samplesLeft` > 0 runs out: the budget ends after the same
    /// iteration as in one process).
    void step(double samplesLeft) override {
        const uint64_t before = comm_.bytesSent();
        if (!mlt_->started()) {
            mlt_->bootstrap();
            bootstrapBytes_ = comm_.bytesSent() - before;
            return;
        }
        if (recordEstimates_ && since_.sums.empty()) mlt_->developSince(since_);  // the sums before
        const uint64_t most = comm_.size() > 1 ? mltIterationsPerRankStep(mlt_->settings()) : 1;
        // Renderer::finished() stops at samplesPerPixel() >= its target; stopping a step a little
        // early (the tolerance covers the rounding of target - before + before) only adds a step.
        const double target = mlt_->mutationsPerPixel() + samplesLeft;
        for (uint64_t i = 0; i < most; ++i) {
            if (i > 0 && samplesLeft > 0 && mlt_->mutationsPerPixel() >= target * (1 - 1e-9)) break;
            mlt_->iterate();
            ++iterationsThisRun_;
        }
        if (recordEstimates_) estimate_ = mlt_->developSince(since_);
        iterated_ = true;
        iterationBytes_ += comm_.bytesSent() - before;
    }
    void gatherStatistics() override {
        if (mlt_->started()) mlt_->gatherCounters();
    }
    double samplesPerPixel() const override { return mlt_->mutationsPerPixel(); }
    bool hasImage() const override { return iterated_ || mlt_->stats().iterations > 0; }
    /// Collective over ranks (the splat films are summed): every rank calls it.
    Image develop() const override {
        const uint64_t before = comm_.bytesSent();
        Image image = mlt_->develop();
        developBytes_ = comm_.bytesSent() - before;
        return image;
    }
    SessionCounters counters() const override {
        // This rank's proposals (its chains) and rays.
        const uint64_t proposals = uint64_t(mlt_->localChains()) * mlt_->settings().proposals * iterationsThisRun_;
        return SessionCounters{proposals, mlt_->stats().rays - raysAtLoad_, 0};
    }
    RenderIdentity parameters() const override { return mltIdentity(path_, mlt_->settings()); }
    void save(std::ostream& out) const override { mlt_->save(out); }
    void load(std::istream& in) override {
        mlt_->load(in);
        since_ = {};  // the loaded sums are taken before the next iteration
        iterationsThisRun_ = 0;
        raysAtLoad_ = mlt_->stats().rays;
    }
    bool hasStepEstimates() const override { return true; }
    void recordStepEstimates() override { recordEstimates_ = true; }
    /// The last iteration's splats alone, developed with the render's b (none for the bootstrap).
    const Image* lastStepEstimate() const override { return estimate_.empty() ? nullptr : &estimate_; }
    std::string description() const override {
        const MltSettings& s = mlt_->settings();
        char line[256];
        std::snprintf(line, sizeof line, "device: %s; integrator mlt, %u chains x %u proposals, %s target, %s state, %s splats",
                      deviceName(device_.kind), s.chains, s.proposals, targetName(s.target), stateName(s.state),
                      splatName(s.splat));
        std::string text = line;
        if (comm_.size() > 1)
            text += ", over " + std::to_string(comm_.size()) + " ranks (" + std::to_string(mlt_->localChains()) +
                    " chains on rank " + std::to_string(comm_.rank()) + ")";
        return text;
    }
    void printSummary(std::FILE* out) const override {
        const MltStats& s = mlt_->stats();
        const MltSettings& set = mlt_->settings();
        std::fprintf(out, "mlt         b = %.6g (%llu bootstrap + %llu large-step samples), %s target\n", s.b,
                     (unsigned long long)s.bootstrapSamples, (unsigned long long)s.largeSteps, targetName(set.target));
        std::fprintf(out, "mlt chains  %u x %u proposals, %llu iterations, %.3g mutations/pixel, acceptance %.1f%%\n",
                     set.chains, set.proposals, (unsigned long long)s.iterations, mlt_->mutationsPerPixel(),
                     s.iterations > 0 ? 100.0 * double(s.accepted) / double(uint64_t(set.chains) * s.iterations) : 0.0);
        std::fprintf(out, "mlt memory  %zu bytes/chain (%s state), %s chain state, %s scratch\n", s.bytesPerChain,
                     stateName(set.state), formatBytes(s.stateBytes).c_str(), formatBytes(s.scratchBytes).c_str());
        std::fprintf(out, "mlt time    bootstrap %.3f s, trace %.3f s, advance %.3f s, splat (%s) %.3f s, sort %.3f s\n",
                     s.bootstrapSeconds, s.traceSeconds, s.advanceSeconds, splatName(set.splat), s.splatSeconds,
                     s.sortSeconds);
    }
    std::vector<std::pair<std::string, std::string>> statsJson() const override {
        const MltStats& s = mlt_->stats();
        return {{"mlt_b", identityNumber(s.b)},
                {"mlt_iterations", std::to_string(s.iterations)},
                {"mlt_mutations_per_pixel", identityNumber(mlt_->mutationsPerPixel())},
                {"mlt_accepted", std::to_string(s.accepted)},
                {"mlt_bytes_per_chain", std::to_string(s.bytesPerChain)},
                {"mlt_state_bytes", std::to_string(s.stateBytes)},
                {"mlt_bootstrap_seconds", identityNumber(s.bootstrapSeconds)},
                {"mlt_trace_seconds", identityNumber(s.traceSeconds)},
                {"mlt_splat_seconds", identityNumber(s.splatSeconds)},
                {"mlt_sort_seconds", identityNumber(s.sortSeconds)},
                {"mlt_ranks", std::to_string(comm_.size())},
                {"mlt_chains_this_rank", std::to_string(mlt_->localChains())},
                {"bytes_sent", std::to_string(comm_.bytesSent())},  // this rank's: bootstrap, sums, develops
                {"bytes_sent_per_iteration",
                 identityNumber(iterationsThisRun_ > 0 ? double(iterationBytes_) / double(iterationsThisRun_) : 0.0)},
                {"mlt_bootstrap_bytes_sent", std::to_string(bootstrapBytes_)},
                {"mlt_develop_bytes_sent", std::to_string(developBytes_)}};
    }

private:
    PathSettings path_;
    Device device_;
    Communicator& comm_;
    std::unique_ptr<MltRenderer> mlt_;
    bool iterated_ = false;
    bool recordEstimates_ = false;
    MltRenderer::SplatState since_;  // the splat sums after the last iteration (empty: not taken yet)
    Image estimate_;                 // the last step's batch estimate (empty after the bootstrap)
    uint64_t iterationsThisRun_ = 0, raysAtLoad_ = 0;
    // Bytes this rank sent: the bootstrap's gather, the iterations' counter sums this run, the
    // last develop's film sum.
    uint64_t bootstrapBytes_ = 0, iterationBytes_ = 0;
    mutable uint64_t developBytes_ = 0;
};

}  // namespace

std::string mltGpuRefusal(IntegratorParams& params) {
    if (params.getString("state", "compact", {"compact", "float"}) != "compact")
        return "--mlt-state float is not available on the GPU (its MLT kernels are compiled for the compact state "
               "only); use --mlt-state compact or --device cpu";
    return {};
}

std::unique_ptr<IntegratorSession> makeMltSession(const SessionContext& c) {
    const uint64_t pixels = uint64_t(c.scene.film.width) * uint64_t(c.scene.film.height);
    uint32_t chains = mltDefaultChains(!c.device.isCpu(), pixels);
    if (const uint32_t saved = savedChains(c.resumeFrom)) chains = saved;
    const PathSettings path = readPathSettings(c.params);
    return std::make_unique<MltSession>(c, path, readMltSettings(c.params, chains));
}

std::string describeMlt(IntegratorParams& params) {
    const PathSettings path = readPathSettings(params);
    std::string line;
    for (const IdentityEntry& e : mltIdentity(path, readMltSettings(params, kMltDefaultChains)))
        line += (line.empty() ? "" : ", ") + e.name + " " + e.value;
    return line + " (chains: on a CPU; a GPU's default differs)";
}

}  // namespace caustica
