// xml_entities.h — what the Mitsuba XML parser produces: plugin instances ("entities") with their
// parameters, nested objects and references, each remembering the file and line it came from.
// Nothing here is a scene object yet; scene_builder turns entities into a caustica::Scene
// (pbrt-v4's split between parsing and building).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "caustica/util/spectrum.h"
#include "caustica/util/transform.h"

namespace caustica::mitsuba {

/// Where an element was written: file (as given or resolved from an include) and 1-based line.
struct SourceLocation {
    std::string file;
    int line = 0;
};

enum class PropertyType {
    Float,
    Integer,
    Boolean,
    String,
    Point,
    Vector,
    Rgb,
    Spectrum,
    Transform
};

/// The XML tag of a property type ("float", "rgb", ...).
const char* propertyTypeName(PropertyType type);

/// One parameter (<float name=... value=...>, <rgb>, <transform>...) after $name substitution.
/// `read` is set when a builder asks for it; parameters never read are reported as warnings.
struct Property {
    std::string name;
    PropertyType type = PropertyType::Float;
    double number = 0;     // Float; also Integer (as a double)
    int64_t integer = 0;   // Integer
    bool boolean = false;  // Boolean
    std::string text;      // String
    Vec3f vector;          // Point, Vector
    Spectrum color;        // Rgb, Spectrum (single value)
    Transform transform;   // Transform
    SourceLocation where;
    mutable bool read = false;
};

/// A nested object or a <ref id=...>, resolved after parsing to an index into
/// SceneDescription::objects.
struct ChildRef {
    std::string name;   // the element's name attribute, "" if none
    std::string refId;  // <ref id=...>: the id referred to; "" for a nested object
    int object = -1;
    SourceLocation where;
};

/// One plugin instance: <shape type="obj" id="..."> with what was written inside it.
struct ObjectEntity {
    std::string category;  // element name: shape, bsdf, emitter, sensor, film, rfilter, ...
    std::string type;      // plugin type attribute
    std::string id;        // "" when none was given
    SourceLocation where;
    std::vector<Property> properties;
    std::vector<ChildRef> children;
    bool topLevel = false;  // a direct child of <scene> (or of an included <scene>)

    /// "bsdf 'diffuse'" (+ " (id 'white')"), the way messages name an object.
    std::string describe() const {
        std::string s = category + " '" + type + "'";
        if (!id.empty()) s += " (id '" + id + "')";
        return s;
    }
};

/// Everything the XML files said, in document order.
struct SceneDescription {
    std::string file;                   // the main scene file
    std::vector<std::string> files;     // every XML file read (the main one, then includes)
    std::vector<ObjectEntity> objects;  // nested objects included
    std::vector<int> topLevel;          // indices of the <scene>'s direct children
    std::map<std::string, int> ids;     // id -> object index (aliases included)
    /// <path value="..."/> folders (absolute, latest first): searched for relative file names
    /// before the folder of the XML file that names them, as Mitsuba's file resolver does.
    std::vector<std::string> searchPaths;
};

}  // namespace caustica::mitsuba
