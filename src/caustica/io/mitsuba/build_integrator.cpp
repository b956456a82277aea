// build_integrator.cpp — Mitsuba 3 integrator plugins -> IntegratorDesc.
//
// | plugin | parameters (default)                                                    |
// |--------|-------------------------------------------------------------------------|
// | path   | max_depth (-1 = unbounded), rr_depth (5), hide_emitters (false)         |
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

using IntegratorFn = IntegratorDesc (*)(Params&);
const PluginTable<IntegratorFn> kIntegratorPlugins{{{"path", pathIntegrator}}};

}  // namespace

void buildIntegrator(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    ctx.scene.integrator = kIntegratorPlugins.find(p)(p);
    p.finish(ctx.warnings);
}

}  // namespace caustica::mitsuba
