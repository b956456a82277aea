// scene_loader.h — the public entry for scene files. Today: Mitsuba 3 XML (with OBJ and PLY
// meshes and Mitsuba's built-in shapes); docs/SCENE_FORMAT.md lists what is supported.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "caustica/scene/scene.h"

namespace caustica {

/// Loads a Mitsuba 3 XML scene. `defines` override <default> values ($name substitution, CLI -D
/// k=v). Throws caustica::Error naming file, line and reason. Warnings (e.g. parameters given but
/// never read) are appended to *warnings when non-null, else printed to stderr.
Scene loadScene(const std::string& path, const std::map<std::string, std::string>& defines = {},
                std::vector<std::string>* warnings = nullptr);

}  // namespace caustica
