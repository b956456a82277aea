#include "render_mlt.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "caustica/integrators/mlt/mlt_loop.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_integrator.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica::cli {

void addMltOptions(CLI::App& cmd, MltCliOptions& o) {
    cmd.add_option("--mlt-chains", o.chains, "MLT: Markov chains stepped in lock step (default 1024 on the CPU; on a GPU half a chain "
                   "per pixel, 4096 to 524288; with --resume, the checkpoint's)")
        ->check(CLI::Range(1u, kMltMaxChains));
    cmd.add_option("--mlt-bootstrap", o.bootstrap,
                   "MLT: ordinary Monte Carlo samples that estimate b and select the chains' starts "
                   "(default 64 per pixel, at most 2^24, at least 4 per chain)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 34));
    cmd.add_option("--mlt-large-step", o.largeStep, "MLT: probability of a large step (default 0.1)")
        ->check(CLI::Range(0.0, 1.0));
    cmd.add_option("--mlt-proposals", o.proposals,
                   "MLT: proposals per step, k (split transitions; 1 = ordinary MLT)")->check(CLI::Range(1u, 64u));
    cmd.add_option("--mlt-s1", o.s1, "MLT: smallest small-step size (default 1/1024)")->check(CLI::Range(1e-7, 0.5));
    cmd.add_option("--mlt-s2", o.s2, "MLT: largest small-step size (default 1/64)")->check(CLI::Range(1e-7, 0.5));
    cmd.add_option("--mlt-state", o.state,
                   "MLT: chain state storage, compact (24/16-bit fixed point) or float (float32)")
        ->check(CLI::IsMember({"compact", "float"}));
    cmd.add_option("--splat", o.splat, "MLT: splat accumulation, atomic or sort (sort + gather, no atomics)")
        ->check(CLI::IsMember({"atomic", "sort"}));
    cmd.add_option("--mlt-sort-every", o.sortEvery,
                   "MLT: Morton-sort the chains every N iterations for coherence (0 = never)");
    cmd.add_option("--mlt-start", o.start,
                   "MLT: chain starts, bootstrap (in proportion to luminance) or uniform (for "
                   "start-up bias experiments)")
        ->check(CLI::IsMember({"bootstrap", "uniform"}));
    cmd.add_option("--mlt-target", o.target,
                   "MLT: target function, relative (default: luminance over the pixel's smoothed bootstrap "
                   "brightness, for even relative error) or luminance (Kelemen's)")
        ->check(CLI::IsMember({"luminance", "relative"}));
}

MltSettings mltSettingsFrom(const IntegratorDesc& desc, const MltCliOptions& o, bool gpu, uint64_t pixels) {
    MltSettings s;
    s.chains = mltDefaultChains(gpu, pixels);
    if (desc.mltChains > 0) s.chains = desc.mltChains;
    if (o.chains > 0) s.chains = o.chains;
    s.bootstrapSamples = o.bootstrap > 0 ? o.bootstrap : desc.mltBootstrapSamples;
    s.largeStepProbability = o.largeStep >= 0 ? Float(o.largeStep) : desc.mltLargeStepProbability;
    s.proposals = o.proposals > 0 ? o.proposals : desc.mltProposals;
    if (o.s1 > 0) s.mutation.s1 = Float(o.s1);
    if (o.s2 > 0) s.mutation.s2 = Float(o.s2);
    s.state = parseMltStateKind(o.state);
    s.splat = parseMltSplatKind(o.splat);
    s.start = parseMltStart(o.start);
    s.target = o.target.empty() ? (desc.mltRelativeTarget ? MltTarget::Relative : MltTarget::Luminance)
                                : parseMltTarget(o.target);
    s.sortEvery = o.sortEvery;
    return s;
}

namespace {

void printMltSummary(const MltRenderer& mlt, std::FILE* out) {
    const MltStats& s = mlt.stats();
    const MltSettings& set = mlt.settings();
    std::fprintf(out, "mlt         b = %.6g (%llu bootstrap + %llu large-step samples), %s target\n", s.b,
                 (unsigned long long)s.bootstrapSamples, (unsigned long long)s.largeSteps,
                 set.target == MltTarget::Relative ? "relative" : "luminance");
    std::fprintf(out, "mlt chains  %u x %u proposals, %llu iterations, %.3g mutations/pixel, acceptance %.1f%%\n",
                 set.chains, set.proposals, (unsigned long long)s.iterations, mlt.mutationsPerPixel(),
                 s.iterations > 0 ? 100.0 * double(s.accepted) / double(uint64_t(set.chains) * s.iterations) : 0.0);
    std::fprintf(out, "mlt memory  %zu bytes/chain (%s state), %s chain state, %s scratch\n", s.bytesPerChain,
                 set.state == MltStateKind::Compact ? "compact" : "float", formatBytes(s.stateBytes).c_str(),
                 formatBytes(s.scratchBytes).c_str());
    std::fprintf(out, "mlt time    bootstrap %.3f s, trace %.3f s, advance %.3f s, splat (%s) %.3f s, sort %.3f s\n",
                 s.bootstrapSeconds, s.traceSeconds, s.advanceSeconds,
                 set.splat == MltSplatKind::Atomic ? "atomic" : "sort", s.splatSeconds, s.sortSeconds);
}

}  // namespace

int runMltRender(const Scene& scene, const Accel& accel, const MltSettings& settings, uint64_t seed,
                 const MltRunRequest& r) {
    const std::unique_ptr<MltRenderer> renderer =
        r.makeRenderer ? r.makeRenderer()
                       : std::make_unique<MltRenderer>(scene, accel, pathSettingsFrom(scene.integrator), settings, seed);
    MltRenderer& mlt = *renderer;
    if (r.resume) {
        std::ifstream in(r.checkpoint, std::ios::binary);
        if (!in) throw Error(r.checkpoint + ": no checkpoint to resume from");
        try {
            mlt.load(in);
        } catch (const Error& e) {
            throw Error(r.checkpoint + ": " + e.what());
        }
        std::fprintf(stderr, "resuming from %s at %.4g mutations/pixel\n", r.checkpoint.c_str(), mlt.mutationsPerPixel());
    }
    auto saveState = [&] {
        if (!r.checkpoint.empty())
            writeFileAtomically(r.checkpoint, [&](std::ostream& out) { mlt.save(out); });
    };
    MltBudget budget;
    budget.mutationsPerPixel = r.mutationsPerPixel;
    budget.timeLimit = r.timeLimit;
    budget.cancel = r.cancel;
    std::unique_ptr<ProgressReporter> progress;
    if (!r.quiet) {
        std::fprintf(stderr, "device: %s; integrator mlt, %u chains x %u proposals, %s target, %s state, %s splats\n",
                     r.device.c_str(), settings.chains, settings.proposals,
                     settings.target == MltTarget::Relative ? "relative" : "luminance",
                     settings.state == MltStateKind::Compact ? "compact" : "float",
                     settings.splat == MltSplatKind::Atomic ? "atomic" : "sort");
        progress = std::make_unique<ProgressReporter>("render", r.mutationsPerPixel, r.timeLimit);
    }
    double lastWrite = 0;
    auto spp = [&] { return std::to_string(mlt.mutationsPerPixel()); };
    auto iterationDone = [&](const MltRenderer& m, const RenderStats& stats) {
        if (progress) progress->update(m.mutationsPerPixel());
        if (r.checkpointEvery > 0 && stats.seconds - lastWrite >= r.checkpointEvery) {
            lastWrite = stats.seconds;
            writeImageOutputs(r.outputs, m.develop(), spp(), stats, r.info);
            saveState();
        }
    };
    RenderStats stats = runMlt(mlt, budget, iterationDone);
    if (progress) progress->finish();
    writeImageOutputs(r.outputs, mlt.develop(), spp(), stats, r.info);
    if (stats.cancelled) {
        saveState();
        std::fprintf(stderr, "interrupted: wrote the image after %.4g mutations/pixel and %s (continue with --resume)\n",
                     mlt.mutationsPerPixel(), r.checkpoint.c_str());
    } else if (!r.checkpoint.empty() && std::filesystem::exists(r.checkpoint)) {
        std::filesystem::remove(r.checkpoint);
    }
    printSummary(stats, stdout);
    printMltSummary(mlt, stdout);
    if (!r.statsJson.empty()) {
        const MltStats& s = mlt.stats();
        auto num = [](double v) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.9g", v);
            return std::string(buf);
        };
        writeStatsJson(r.statsJson, stats, r.info, r.buildSeconds,
                       {{"mlt_b", num(s.b)},
                        {"mlt_iterations", std::to_string(s.iterations)},
                        {"mlt_mutations_per_pixel", num(mlt.mutationsPerPixel())},
                        {"mlt_accepted", std::to_string(s.accepted)},
                        {"mlt_bytes_per_chain", std::to_string(s.bytesPerChain)},
                        {"mlt_state_bytes", std::to_string(s.stateBytes)},
                        {"mlt_bootstrap_seconds", num(s.bootstrapSeconds)},
                        {"mlt_trace_seconds", num(s.traceSeconds)},
                        {"mlt_splat_seconds", num(s.splatSeconds)},
                        {"mlt_sort_seconds", num(s.sortSeconds)}});
    }
    return stats.cancelled ? 130 : 0;
}

}  // namespace caustica::cli
