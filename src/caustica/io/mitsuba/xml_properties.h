// xml_properties.h — parsing of Mitsuba's property elements (<float>, <rgb>, <transform>, ...).
#pragma once

#include <pugixml.hpp>

#include "caustica/io/mitsuba/xml_entities.h"
#include "caustica/io/mitsuba/xml_file.h"

namespace caustica::mitsuba {

/// True for the tags parseProperty understands.
bool isPropertyTag(std::string_view tag);

/// Parses one property element (tag is one isPropertyTag accepts) of an object of `category`
/// ("bsdf", "emitter", ...: a <spectrum> converts to RGB differently in emitters, as in Mitsuba).
/// Throws caustica::Error at the element's line for malformed values, missing attributes,
/// NaN/Inf, singular transforms and features not supported (spectrum files).
Property parseProperty(const XmlFile& file, const pugi::xml_node& node,
                       const std::string& category = "");

/// Parses the operations inside <transform>: translate, rotate, scale, matrix, lookat. Each new
/// operation is applied after the previous ones (T = op * T), as in Mitsuba.
Transform parseTransform(const XmlFile& file, const pugi::xml_node& node);

}  // namespace caustica::mitsuba
