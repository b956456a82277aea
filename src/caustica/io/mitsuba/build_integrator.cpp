// build_integrator.cpp — the scene's <integrator> -> IntegratorSpec: its type and its parameters
// as written (each integrator reads and checks its own: integrators/*/..._settings.cpp).
//
// | plugin        | runs as | parameters: see docs/SCENE_FORMAT.md                             |
// |---------------|---------|------------------------------------------------------------------|
// | path          | path    | max_depth, rr_depth, hide_emitters                               |
// | direct        | direct  | shading_samples, emitter_samples, bsdf_samples, hide_emitters    |
// | mlt, pssmlt   | mlt     | the path parameters, chains, luminance_samples, p_large, ...     |
// | sppm, ppm     | same    | the photon mappers' parameters (docs/SPPM.md)                    |
// | whitted       | whitted | max_depth, rr_depth, hide_emitters (caustica's own, not Mitsuba) |
// | aov           | nested  | aovs (film/aov_layers.h): AOV layers beside the nested integrator |
//
// Other Mitsuba integrators (volpath, volpathmis, prb, ptracer, depth, ... and Mitsuba 0.6's
// bdpt, ...) are rendered with the nearest caustica integrator, with a warning naming the
// file:line, the original and the replacement: an integrator that wraps others (moment)
// becomes its first nested integrator, direct_projective becomes direct, everything else path
// (which reads the parameters it shares, e.g. max_depth, and warns about the rest).
#include <cstdio>
#include <string>

#include "caustica/film/aov_layers.h"
#include "caustica/io/mitsuba/build_context.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

/// The caustica integrator a Mitsuba type runs as, or "" when it has none of its own.
std::string nativeType(const std::string& type) {
    if (type == "path" || type == "direct" || type == "mlt" || type == "sppm" || type == "ppm" ||
        type == "whitted")
        return type;
    if (type == "pssmlt") return "mlt";  // Mitsuba 0.6's name; the same parameters
    return {};
}

IntegratorParam specParam(const Property& p) {
    IntegratorParam out;
    out.name = p.name;
    out.where = p.where.file + ":" + std::to_string(p.where.line);
    char buf[32];
    switch (p.type) {
        case PropertyType::Integer:
            out.kind = IntegratorParam::Kind::Integer;
            out.text = std::to_string(p.integer);
            break;
        case PropertyType::Float:
            out.kind = IntegratorParam::Kind::Float;
            std::snprintf(buf, sizeof buf, "%.17g", p.number);
            out.text = buf;
            break;
        case PropertyType::Boolean:
            out.kind = IntegratorParam::Kind::Boolean;
            out.text = p.boolean ? "true" : "false";
            break;
        default:  // <string>, and the types no integrator reads (refused if one tries)
            out.kind = IntegratorParam::Kind::String;
            out.text = p.type == PropertyType::String ? p.text : std::string("<") + propertyTypeName(p.type) + ">";
            break;
    }
    return out;
}

std::string lineOf(const SourceLocation& at) { return at.file + ":" + std::to_string(at.line); }

IntegratorSpec buildSpec(BuildContext& ctx, int object);

/// Mitsuba's aov integrator: the first nested integrator renders the image, the `aovs` list
/// (checked here, so that a bad one names its line) travels with it.
IntegratorSpec buildAovSpec(BuildContext& ctx, int object) {
    const ObjectEntity& e = ctx.desc.objects[size_t(object)];
    const std::string where = lineOf(e.where);
    const Property* list = nullptr;
    for (const Property& p : e.properties) {
        p.read = true;
        if (p.name == "aovs" && p.type == PropertyType::String) {
            list = &p;
        } else {
            ctx.warnings.push_back(lineOf(p.where) + ": parameter '" + p.name + "' of integrator 'aov' is not used");
        }
    }
    if (!list) throw Error(e.where.file, e.where.line, "integrator 'aov' needs a <string name=\"aovs\">");
    const std::string listWhere = lineOf(list->where);
    parseAovSpec(list->text, listWhere);  // refuses a bad list with its file:line
    IntegratorSpec spec;
    bool nested = false;
    for (const ChildRef& child : e.children) {
        const ObjectEntity& inner = ctx.desc.objects[size_t(child.object)];
        if (inner.category != "integrator")
            throw Error(child.where.file, child.where.line, "integrator 'aov' takes no nested " + inner.category);
        if (nested) {
            ctx.warnings.push_back(lineOf(inner.where) + ": integrator '" + inner.type +
                                   "' is not used (caustica renders the first integrator nested in 'aov')");
            continue;
        }
        nested = true;
        spec = buildSpec(ctx, child.object);
        if (!spec.aovs.empty())
            throw Error(inner.where.file, inner.where.line, "an aov integrator nested in an aov integrator");
    }
    if (!nested) {
        ctx.used.insert(object);
        spec.where = where;
        ctx.warnings.push_back(where + ": integrator 'aov' holds no integrator: rendering the image with 'path'");
    }
    spec.aovs = list->text;
    spec.aovsWhere = listWhere;
    return spec;
}

IntegratorSpec buildSpec(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    const ObjectEntity& e = ctx.desc.objects[size_t(object)];
    const std::string where = e.where.file + ":" + std::to_string(e.where.line);
    if (e.type == "aov") return buildAovSpec(ctx, object);
    IntegratorSpec spec;
    spec.where = where;
    spec.type = nativeType(e.type);
    if (spec.type.empty()) {
        for (const ChildRef& child : e.children) {
            const ObjectEntity& inner = ctx.desc.objects[size_t(child.object)];
            if (inner.category != "integrator") continue;
            ctx.warnings.push_back(where + ": integrator '" + e.type +
                                   "' is not supported by caustica: rendering with its nested integrator '" +
                                   inner.type + "' (line " + std::to_string(inner.where.line) + ") instead");
            for (const Property& p : e.properties) {
                p.read = true;
                ctx.warnings.push_back(p.where.file + ":" + std::to_string(p.where.line) + ": parameter '" + p.name +
                                       "' is not used (integrator '" + e.type + "' renders its nested one)");
            }
            return buildSpec(ctx, child.object);
        }
        spec.type = e.type == "direct_projective" ? "direct" : "path";
        ctx.warnings.push_back(where + ": integrator '" + e.type + "' is not supported by caustica: rendering with '" +
                               spec.type + "' instead");
    }
    for (const ChildRef& child : e.children)
        throw Error(child.where.file, child.where.line,
                    "integrator '" + e.type + "' takes no nested " + ctx.desc.objects[size_t(child.object)].category);
    for (const Property& p : e.properties) {
        p.read = true;
        spec.params.push_back(specParam(p));
    }
    return spec;
}

}  // namespace

void buildIntegrator(BuildContext& ctx, int object) {
    ctx.scene.integrator = buildSpec(ctx, object);
}

}  // namespace caustica::mitsuba
