#include "caustica/integrators/mlt/mlt_settings.h"

namespace caustica {

MltSettings readMltSettings(IntegratorParams& p, uint32_t defaultChains) {
    MltSettings s;
    s.chains = uint32_t(p.getInt("chains", defaultChains, 1, kMltMaxChains));
    s.bootstrapSamples = uint64_t(p.getInt("luminance_samples", 0, 1, int64_t(1) << 34));
    s.largeStepProbability = Float(p.getFloat("p_large", 0.1, 0, 1));
    s.proposals = uint32_t(p.getInt("proposals", 1, 1, 64));
    s.target = parseMltTarget(p.getString("target", "relative", {"relative", "luminance"}));
    s.mutation.s1 = Float(p.getFloat("s1", double(s.mutation.s1), 1e-7, 0.5));
    s.mutation.s2 = Float(p.getFloat("s2", double(s.mutation.s2), 1e-7, 0.5));
    s.state = parseMltStateKind(p.getString("state", "compact", {"compact", "float"}));
    s.splat = parseMltSplatKind(p.getString("splat", "atomic", {"atomic", "sort"}));
    s.sortEvery = uint32_t(p.getInt("sort_every", 0, 0, UINT32_MAX));
    s.start = parseMltStart(p.getString("start", "bootstrap", {"bootstrap", "uniform"}));
    return s;
}

const std::vector<IntegratorOption>& mltOptions() {
    static const std::vector<IntegratorOption> options = {
        {"--mlt-chains", "chains", "MLT: Markov chains stepped in lock step (default 1024 on the CPU; on a GPU half "
                                   "a chain per pixel, 4096 to 524288; with --resume, the checkpoint's)"},
        {"--mlt-bootstrap", "luminance_samples", "MLT: ordinary Monte Carlo samples that estimate b and select the "
                                                 "chains' starts (default 64 per pixel, at most 2^24, at least 4 per chain)"},
        {"--mlt-large-step", "p_large", "MLT: probability of a large step, in [0, 1] (default 0.1)"},
        {"--mlt-proposals", "proposals", "MLT: proposals per step, k, 1..64 (split transitions; 1 = ordinary MLT)"},
        {"--mlt-target", "target", "MLT: target function, relative (default: luminance over the pixel's smoothed "
                                   "bootstrap brightness) or luminance (Kelemen's)"},
        {"--mlt-s1", "s1", "MLT: smallest small-step size, in [1e-7, 0.5] (default 1/1024)"},
        {"--mlt-s2", "s2", "MLT: largest small-step size, in [1e-7, 0.5] (default 1/64)"},
        {"--mlt-state", "state", "MLT: chain state storage, compact (24/16-bit fixed point) or float"},
        {"--splat", "splat", "MLT: splat accumulation, atomic or sort (sort + gather, no atomics)"},
        {"--mlt-sort-every", "sort_every", "MLT: Morton-sort the chains every N iterations (0 = never)"},
        {"--mlt-start", "start", "MLT: chain starts, bootstrap (in proportion to luminance) or uniform (for "
                                 "start-up bias experiments)"},
    };
    return options;
}

}  // namespace caustica
