#include "caustica/io/mitsuba/scene_builder.h"

#include <filesystem>

#include "caustica/io/mitsuba/build_context.h"
#include "caustica/scene/light_setup.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

uint32_t BuildContext::bsdf(int object) {
    used.insert(object);
    if (auto it = bsdfIndex_.find(object); it != bsdfIndex_.end()) return it->second;
    const ObjectEntity& e = desc.objects[size_t(object)];
    if (e.category != "bsdf")
        throw Error(e.where.file, e.where.line, e.describe() + " is used where a bsdf is expected");
    if (!inProgress_.insert(object).second)
        throw Error(e.where.file, e.where.line,
                    e.describe() + " refers to itself (reference cycle)");
    Params params(desc, object);
    Bsdf record = buildBsdfRecord(*this, params);
    params.finish(warnings);
    inProgress_.erase(object);
    uint32_t index = uint32_t(scene.bsdfs.size());
    scene.bsdfs.push_back(record);
    bsdfIndex_[object] = index;
    return index;
}

uint32_t BuildContext::defaultBsdf(bool emitter) {
    int64_t& index = emitter ? defaultEmitterBsdf_ : defaultBsdf_;
    if (index < 0) {
        index = int64_t(scene.bsdfs.size());
        Bsdf b;
        b.type = BsdfType::Diffuse;
        b.reflectance = Spectrum(emitter ? 0.0f : 0.5f);
        scene.bsdfs.push_back(b);
    }
    return uint32_t(index);
}

std::string BuildContext::resolvePath(const ObjectEntity& object, const std::string& file) const {
    namespace fs = std::filesystem;
    fs::path p(file);
    if (p.is_absolute()) return recordInput(p.string());
    // Mitsuba's file resolver: the <path> folders (latest first), then the declaring file's folder.
    std::error_code ec;
    for (const std::string& dir : desc.searchPaths) {
        fs::path candidate = (fs::path(dir) / p).lexically_normal();
        if (fs::exists(candidate, ec)) return recordInput(candidate.string());
    }
    return recordInput((fs::path(object.where.file).parent_path() / p).lexically_normal().string());
}

const std::string& BuildContext::recordInput(const std::string& path) const {
    scene.inputFiles.push_back(path);
    return path;
}

Scene buildScene(const SceneDescription& desc, std::vector<std::string>& warnings) {
    Scene scene;
    scene.sourceFile = desc.file;
    scene.inputFiles = desc.files;
    BuildContext ctx(desc, scene, warnings);
    int sensor = -1, integrator = -1;
    for (int index : desc.topLevel) {
        const ObjectEntity& e = desc.objects[size_t(index)];
        if (e.category == "shape") {
            buildShape(ctx, index);
        } else if (e.category == "emitter") {
            if (e.type != "area") buildEmitter(ctx, index, -1);
        } else if (e.category == "sensor") {
            if (sensor >= 0) {
                warnings.push_back(e.where.file + ":" + std::to_string(e.where.line) +
                                   ": only the first sensor is rendered; this one is ignored");
                ctx.used.insert(index);
                continue;
            }
            sensor = index;
            buildSensor(ctx, index);
        } else if (e.category == "integrator") {
            if (integrator >= 0) {
                const SourceLocation& first = desc.objects[size_t(integrator)].where;
                throw Error(e.where.file, e.where.line,
                            "a second integrator (the first is at line " +
                                std::to_string(first.line) + ")");
            }
            integrator = index;
            buildIntegrator(ctx, index);
        }
    }
    // Objects declared at the top level to be referenced (bsdfs, films...) but never used.
    for (int index : desc.topLevel) {
        const ObjectEntity& e = desc.objects[size_t(index)];
        if (ctx.used.count(index) || e.category == "shape" || e.category == "sensor" ||
            e.category == "integrator" || (e.category == "emitter" && e.type != "area"))
            continue;
        if (e.category == "emitter")
            throw Error(e.where.file, e.where.line,
                        "an area emitter must be nested in (or referenced by) a shape");
        warnings.push_back(e.where.file + ":" + std::to_string(e.where.line) + ": " + e.describe() +
                           " is declared but never used");
    }
    if (sensor < 0) throw Error(desc.file, 0, "scene has no sensor");
    finalizeLights(scene);
    reserveVertexPadding(scene);
    return scene;
}

}  // namespace caustica::mitsuba
