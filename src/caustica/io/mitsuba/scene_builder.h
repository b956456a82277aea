// scene_builder.h — turns parsed Mitsuba entities into caustica's flat Scene.
#pragma once

#include <string>
#include <vector>

#include "caustica/io/mitsuba/xml_entities.h"
#include "caustica/scene/scene.h"

namespace caustica::mitsuba {

/// Builds every top-level shape, emitter, sensor and integrator (and what they reference), then
/// calls finalizeLights. Throws caustica::Error (file:line: reason); appends warnings for
/// parameters never read and named objects never used.
Scene buildScene(const SceneDescription& desc, std::vector<std::string>& warnings);

}  // namespace caustica::mitsuba
