// build_emitters.cpp — Mitsuba 3 emitter plugins -> caustica::Light records.
//
// | plugin   | parameters (default)                                                  |
// |----------|-----------------------------------------------------------------------|
// | area     | radiance (1); only inside (or referenced by) a shape                  |
// | point    | intensity (1), position (0, 0, 0) or to_world (not both)              |
// | constant | radiance (1); at most one environment (constant or envmap) per scene   |
// | spot     | intensity (1), cutoff_angle (20), beam_width (3/4 cutoff), to_world,      |
// |          | texture (none; a spatially varying texture over the cone)             |
// | directional | irradiance (1), direction (0, 0, 1) or to_world (not both)             |
// | envmap   | filename (.exr, .hdr, .pfm, .png), scale (1), to_world; one environment   |
#include <cmath>

#include "caustica/io/image_io.h"
#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/build_textures.h"
#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/util/error.h"

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

/// Mitsuba 3 refuses a second environment emitter ("Only one environment emitter can be
/// specified per scene"); directional emitters do not count.
void requireSingleEnvironment(EmitterArgs& a) {
    for (const Light& other : a.ctx.scene.lights)
        if (other.type == LightType::Constant || other.type == LightType::EnvMap)
            a.params.fail("a scene can have only one environment emitter (constant or envmap)");
}

/// Rows of the linear part of `t` (and of its inverse when `inverse`).
void linearRows(const Transform& t, bool inverse, Vec3f (&rows)[3]) {
    const Matrix4& m = inverse ? t.mInv : t.m;
    for (int r = 0; r < 3; ++r) rows[r] = Vec3f(m.m[r][0], m.m[r][1], m.m[r][2]);
}

Light constantEmitter(EmitterArgs& a) {
    requireSingleEnvironment(a);
    Light l;
    l.type = LightType::Constant;
    l.radiance = a.params.getSpectrum("radiance", Spectrum(1.0f));
    return l;
}

/// Mitsuba 3's spot: cutoff_angle and beam_width in degrees, linear falloff between them.
Light spotEmitter(EmitterArgs& a) {
    Params& p = a.params;
    Light l;
    l.type = LightType::Spot;
    l.radiance = p.getSpectrum("intensity", Spectrum(1.0f));
    const double cutoff = p.getFloat("cutoff_angle", 20.0f);
    const double beam = p.getFloat("beam_width", Float(cutoff * 0.75));
    if (!(cutoff > 0 && cutoff <= 180)) p.fail(*p.find("cutoff_angle"), "must be in (0, 180] degrees");
    if (!(beam >= 0 && beam <= cutoff))
        p.fail(*p.find("beam_width"), "must be between 0 and cutoff_angle");
    const double deg = M_PI / 180.0;
    l.cutoff = Float(cutoff * deg);
    l.cosCutoff = Float(std::cos(cutoff * deg));
    l.cosBeam = Float(std::cos(beam * deg));
    // cutoff == beam_width: a hard edge (Mitsuba divides by zero there; never used in between).
    l.invTransition = beam < cutoff ? Float(1.0 / ((cutoff - beam) * deg)) : Float(0);
    const Transform t = p.getTransform("to_world");
    l.position = t.applyPoint(Vec3f(0));
    linearRows(t, true, l.localFromWorld);
    l.uvFactor = Float(std::tan(Float(cutoff * deg)));
    if (const int tex = findTextureChild(p, "texture"); tex >= 0) {
        p.takeChildren("texture");
        l.texture = buildTexture(a.ctx, tex);
        if (a.ctx.scene.textures[l.texture].type == TextureType::Constant)
            p.failAtChild(tex, "'texture' must be spatially varying, e.g. a bitmap (as Mitsuba 3)");
    } else if (p.has("texture")) {
        p.fail(*p.find("texture"),
               "must be a spatially varying texture, e.g. a bitmap (as Mitsuba 3)");
    }
    return l;
}

/// Mitsuba 3's directional: `direction`, or to_world's +z, is the direction the light travels.
Light directionalEmitter(EmitterArgs& a) {
    Params& p = a.params;
    Light l;
    l.type = LightType::Directional;
    l.radiance = p.getSpectrum("irradiance", Spectrum(1.0f));
    if (p.has("direction") && p.has("to_world"))
        p.fail("give either 'direction' or 'to_world', not both");
    const Vec3f d = p.has("direction") ? p.getPoint("direction", Vec3f(0, 0, 1))
                                       : p.getTransform("to_world").applyVector(Vec3f(0, 0, 1));
    if (!isFinite(d) || !(length(d) > 0)) p.fail("the emission direction must be a nonzero vector");
    l.direction = normalize(d);
    return l;
}

/// Mitsuba 3's envmap: a lat-long radiance image (light_envmap.h), times `scale`.
Light envmapEmitter(EmitterArgs& a) {
    Params& p = a.params;
    requireSingleEnvironment(a);
    const Property* file = p.find("filename");
    const std::string path = a.ctx.resolvePath(p.object(), p.getString("filename"));
    Image image;
    try {
        image = readImage(path);
    } catch (const Error& e) {
        throw Error(file->where.file, file->where.line, p.object().describe() + ": " + e.what());
    }
    if (image.width < 2 || image.height < 3)
        p.fail(*file, "the environment map must be at least 2x3 pixels (as in Mitsuba)");
    if (!image.allFinite()) p.fail(*file, "the environment map has non-finite pixels");
    const Float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0)) p.fail(*p.find("scale"), "must not be negative");
    if (p.getBool("mis_compensation", false))
        p.fail(*p.find("mis_compensation"), "(MIS compensation) is not supported yet");

    Light l;
    l.type = LightType::EnvMap;
    l.radiance = Spectrum(scale);
    const Transform t = p.getTransform("to_world");
    linearRows(t, true, l.localFromWorld);
    linearRows(t, false, l.worldFromLocal);
    std::vector<Spectrum>& texels = a.ctx.scene.lightTexels;
    l.texOffset = uint32_t(texels.size());
    l.texWidth = uint32_t(image.width);
    l.texHeight = uint32_t(image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Spectrum v = image.at(x, y);
            if (v.r < 0 || v.g < 0 || v.b < 0)
                p.fail(*file, "the environment map has negative pixels");
            texels.push_back(v * scale);
        }
    return l;
}

using EmitterFn = Light (*)(EmitterArgs&);
const PluginTable<EmitterFn> kEmitterPlugins{
    {{"area", areaEmitter},
     {"constant", constantEmitter},
     {"directional", directionalEmitter},
     {"envmap", envmapEmitter},
     {"point", pointEmitter},
     {"spot", spotEmitter}}};

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
