// build_emitters.cpp — Mitsuba 3 emitter plugins -> caustica::Light records.
//
// | plugin   | parameters (default)                                                  |
// |----------|-----------------------------------------------------------------------|
// | area     | radiance (1); only inside (or referenced by) a shape                  |
// | point    | intensity (1), position (0, 0, 0) or to_world (not both)              |
// | constant | radiance (1); at most one per scene                                   |
#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/plugin_table.h"

namespace caustica::mitsuba {

namespace {

struct EmitterArgs {
    BuildContext& ctx;
    Params& params;
    int32_t shape;  // the shape an area emitter is attached to, -1 at the top level
};

Light areaEmitter(EmitterArgs& a) {
    if (a.shape < 0) a.params.fail("an area emitter must be nested in (or referenced by) a shape");
    Light l;
    l.type = LightType::Area;
    l.radiance = a.params.getSpectrum("radiance", Spectrum(1.0f));
    l.shape = uint32_t(a.shape);
    return l;
}

Light pointEmitter(EmitterArgs& a) {
    Light l;
    l.type = LightType::Point;
    l.radiance = a.params.getSpectrum("intensity", Spectrum(1.0f));
    if (a.params.has("position") && a.params.has("to_world"))
        a.params.fail("give either 'position' or 'to_world', not both");
    if (a.params.has("to_world"))
        l.position = a.params.getTransform("to_world").applyPoint(Vec3f(0));
    else
        l.position = a.params.getPoint("position", Vec3f(0));
    if (!isFinite(l.position)) a.params.fail("position is not finite");
    return l;
}

Light constantEmitter(EmitterArgs& a) {
    for (const Light& other : a.ctx.scene.lights)
        if (other.type == LightType::Constant)
            a.params.fail("a scene can have only one environment emitter (constant)");
    Light l;
    l.type = LightType::Constant;
    l.radiance = a.params.getSpectrum("radiance", Spectrum(1.0f));
    return l;
}

using EmitterFn = Light (*)(EmitterArgs&);
const PluginTable<EmitterFn> kEmitterPlugins{
    {{"area", areaEmitter}, {"constant", constantEmitter}, {"point", pointEmitter}}};

}  // namespace

void buildEmitter(BuildContext& ctx, int object, int32_t shape) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    EmitterArgs args{ctx, p, shape};
    Light light = kEmitterPlugins.find(p)(args);
    p.finish(ctx.warnings);
    const uint32_t index = uint32_t(ctx.scene.lights.size());
    ctx.scene.lights.push_back(light);
    if (light.type == LightType::Area) ctx.scene.shapes[size_t(shape)].light = int32_t(index);
}

}  // namespace caustica::mitsuba
