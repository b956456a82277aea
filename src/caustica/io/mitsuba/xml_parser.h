// xml_parser.h — reads Mitsuba 3 XML (with its includes) into entities; builds nothing.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "caustica/io/mitsuba/xml_entities.h"

namespace caustica::mitsuba {

/// Parses `path`: <scene version>, <include> (relative to the including file, cycles refused),
/// <default> and $name substitution (`defines` win over <default>), objects with their
/// properties, nested objects and <ref>s (resolved to object indices; unknown and duplicate ids
/// refused). Scenes older than version 2.0.0 get Mitsuba 3's in-memory upgrade (camelCase
/// parameter names to snake_case, <lookAt> to <lookat>). Throws caustica::Error with file and
/// line; appends warnings (e.g. defines never used) to `warnings`.
SceneDescription parseSceneXml(const std::string& path,
                               const std::map<std::string, std::string>& defines,
                               std::vector<std::string>& warnings);

}  // namespace caustica::mitsuba
