// build_context.h — the state shared by the plugin builders while a Scene is assembled from
// parsed entities, and the entry point of each object category (one file each).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "caustica/io/mitsuba/params.h"
#include "caustica/scene/scene.h"

namespace caustica::mitsuba {

class BuildContext {
public:
    BuildContext(const SceneDescription& desc, Scene& scene, std::vector<std::string>& warnings)
        : desc(desc), scene(scene), warnings(warnings) {}

    const SceneDescription& desc;
    Scene& scene;
    std::vector<std::string>& warnings;

    /// Index of the BSDF built from `object`, building it (and its children) on first use, so
    /// that a referenced BSDF is one record however many shapes use it.
    uint32_t bsdf(int object);
    /// Mitsuba's BSDF for shapes without one (created once each): diffuse, reflectance 0.5, or
    /// reflectance 0 for a shape with an area emitter (as Mitsuba 3's Shape constructor does).
    uint32_t defaultBsdf(bool emitter = false);
    /// `file` found in the scene's <path> folders (latest first), else relative to the XML file
    /// that declared `object` (absolute paths unchanged).
    /// The resolved path is recorded in scene.inputFiles.
    std::string resolvePath(const ObjectEntity& object, const std::string& file) const;

    std::set<int> used;  // objects built or referenced (unused named objects get a warning)
    std::map<int, uint32_t> textureIndex;  // <texture> object -> Scene::textures (build_textures.cpp)

private:
    /// Appends `path` to scene.inputFiles (Scene is held by reference) and returns it.
    const std::string& recordInput(const std::string& path) const;

    std::map<int, uint32_t> bsdfIndex_;
    std::set<int> inProgress_;
    int64_t defaultBsdf_ = -1, defaultEmitterBsdf_ = -1;
};

/// The category builders. Each reads its entity through Params and appends to ctx.scene.
Bsdf buildBsdfRecord(BuildContext& ctx, Params& params);          // build_bsdfs.cpp
void buildShape(BuildContext& ctx, int object);                   // build_shapes.cpp
void buildEmitter(BuildContext& ctx, int object, int32_t shape);  // build_emitters.cpp
void buildSensor(BuildContext& ctx, int object);                  // build_sensor.cpp
void buildIntegrator(BuildContext& ctx, int object);              // build_integrator.cpp

}  // namespace caustica::mitsuba
