// build_integrator.cpp — Mitsuba 3 integrator plugins -> IntegratorDesc.
//
// | plugin | parameters (default)                                                    |
// |--------|-------------------------------------------------------------------------|
// | path   | max_depth (-1 = unbounded), rr_depth (5), hide_emitters (false)         |
// | direct | shading_samples (1), emitter_samples (shading_samples),                 |
// |        | bsdf_samples (shading_samples), hide_emitters (false)                   |
//
// Other Mitsuba integrators (volpath, volpathmis, prb, ptracer, aov, depth, ... and Mitsuba 0.6's
// bdpt, sppm, ...) are rendered with the nearest caustica integrator, with a warning naming the
// file:line, the original and the replacement: an integrator that wraps others (aov, moment)
// becomes its first nested integrator, direct_projective becomes direct, everything else path
// (reading the path parameters it shares: max_depth, rr_depth, hide_emitters).
#include <string>

#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/plugin_table.h"

namespace caustica::mitsuba {

namespace {

IntegratorDesc pathIntegrator(Params& p) {
    IntegratorDesc d;
    d.type = IntegratorType::Path;
    d.maxDepth = p.getInt("max_depth", -1);
    if (d.maxDepth < -1) p.fail(*p.find("max_depth"), "must be -1 (unbounded) or >= 0");
    d.rrDepth = p.getInt("rr_depth", 5);
    if (d.rrDepth <= 0) p.fail(*p.find("rr_depth"), "must be greater than zero");
    d.hideEmitters = p.getBool("hide_emitters", false);
    return d;
}

/// Mitsuba 3's direct.cpp: shading_samples sets both counts and may not be combined with them;
/// at least one sample in all.
IntegratorDesc directIntegrator(Params& p) {
    IntegratorDesc d;
    d.type = IntegratorType::Direct;
    if (p.has("shading_samples") && (p.has("emitter_samples") || p.has("bsdf_samples")))
        p.fail(*p.find("shading_samples"),
               "cannot be combined with 'emitter_samples' or 'bsdf_samples'");
    auto count = [&](const char* name, int def) {
        const int n = p.getInt(name, def);
        if (n < 0) p.fail(*p.find(name), "must be >= 0");
        return n;
    };
    const int shading = count("shading_samples", 1);
    d.emitterSamples = count("emitter_samples", shading);
    d.bsdfSamples = count("bsdf_samples", shading);
    if (d.emitterSamples + d.bsdfSamples == 0)
        p.fail("needs at least one emitter or BSDF sample (emitter_samples + bsdf_samples > 0)");
    d.hideEmitters = p.getBool("hide_emitters", false);
    return d;
}

/// caustica's Metropolis light transport (mlt; Mitsuba 0.6's pssmlt reads the same): the path
/// parameters plus chains, luminance_samples (bootstrap), p_large (Mitsuba 0.6's pLarge),
/// proposals and target (luminance | relative).
IntegratorDesc mltIntegrator(Params& p) {
    IntegratorDesc d = pathIntegrator(p);
    d.type = IntegratorType::Mlt;
    const int chains = p.getInt("chains", 0);
    if (chains < 0) p.fail(*p.find("chains"), "must be >= 0 (0: the default)");
    d.mltChains = uint32_t(chains);
    const int bootstrap = p.getInt("luminance_samples", 0);
    if (bootstrap < 0) p.fail(*p.find("luminance_samples"), "must be >= 0 (0: the default)");
    d.mltBootstrapSamples = uint64_t(bootstrap);
    d.mltLargeStepProbability = p.getFloat("p_large", 0.1f);
    if (!(d.mltLargeStepProbability >= 0 && d.mltLargeStepProbability <= 1))
        p.fail(*p.find("p_large"), "must be in [0, 1]");
    const int k = p.getInt("proposals", 1);
    if (k < 1 || k > 64) p.fail(*p.find("proposals"), "must be in 1..64");
    d.mltProposals = uint32_t(k);
    const std::string target = p.getString("target", "relative");
    if (target != "luminance" && target != "relative")
        p.fail(*p.find("target"), "must be luminance or relative, not '" + target + "'");
    d.mltRelativeTarget = target == "relative";
    return d;
}

using IntegratorFn = IntegratorDesc (*)(Params&);
const PluginTable<IntegratorFn> kIntegratorPlugins{
    {{"path", pathIntegrator}, {"direct", directIntegrator}, {"mlt", mltIntegrator}, {"pssmlt", mltIntegrator}}};

/// Types that are not mapped to the nearest integrator when unsupported: Metropolis light
/// transport is its own integrator (the table's "unsupported" error until it is in the table).
bool neverMapped(const std::string& type) {
    return type == "mlt" || type == "pssmlt";
}

bool inTable(const std::string& type) {
    for (const auto& entry : kIntegratorPlugins.entries)
        if (entry.first == type) return true;
    return false;
}

IntegratorDesc buildDesc(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    const ObjectEntity& e = p.object();
    IntegratorDesc d;
    if (inTable(e.type) || neverMapped(e.type)) {
        d = kIntegratorPlugins.find(p)(p);
    } else {
        const std::string where = e.where.file + ":" + std::to_string(e.where.line) + ": ";
        const std::vector<int> nested = p.takeChildren("integrator");
        if (!nested.empty()) {
            const ObjectEntity& inner = ctx.desc.objects[size_t(nested[0])];
            ctx.warnings.push_back(where + "integrator '" + e.type +
                                   "' is not supported by caustica: rendering with its nested "
                                   "integrator '" + inner.type + "' (line " +
                                   std::to_string(inner.where.line) + ") instead");
            d = buildDesc(ctx, nested[0]);
        } else {
            const bool direct = e.type == "direct_projective";
            ctx.warnings.push_back(where + "integrator '" + e.type +
                                   "' is not supported by caustica: rendering with '" +
                                   (direct ? "direct" : "path") + "' instead");
            d = direct ? directIntegrator(p) : pathIntegrator(p);
        }
    }
    p.finish(ctx.warnings);
    return d;
}

}  // namespace

void buildIntegrator(BuildContext& ctx, int object) {
    ctx.scene.integrator = buildDesc(ctx, object);
}

}  // namespace caustica::mitsuba
