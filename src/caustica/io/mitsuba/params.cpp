#include "caustica/io/mitsuba/params.h"

#include <climits>
#include <cmath>

#include "caustica/util/error.h"

namespace caustica::mitsuba {

Params::Params(const SceneDescription& desc, int object)
    : desc_(desc),
      object_(&desc.objects[size_t(object)]),
      taken_(object_->children.size(), false) {}

bool Params::has(const std::string& name) const {
    for (const Property& p : object_->properties)
        if (p.name == name) return true;
    return false;
}

const Property* Params::find(const std::string& name) const {
    for (const Property& p : object_->properties)
        if (p.name == name) {
            p.read = true;
            return &p;
        }
    return nullptr;
}

const Property& Params::require(const std::string& name) const {
    const Property* p = find(name);
    if (!p) fail("missing required parameter '" + name + "'");
    return *p;
}

void Params::fail(const std::string& reason) const {
    throw Error(object_->where.file, object_->where.line, object_->describe() + ": " + reason);
}

void Params::fail(const Property& at, const std::string& reason) const {
    throw Error(at.where.file, at.where.line,
                object_->describe() + ": parameter '" + at.name + "' " + reason);
}

void Params::failAtChild(int childObject, const std::string& reason) const {
    const ObjectEntity& c = desc_.objects[size_t(childObject)];
    for (const ChildRef& r : object_->children)
        if (r.object == childObject)
            throw Error(r.where.file, r.where.line, object_->describe() + ": " + reason);
    throw Error(c.where.file, c.where.line, object_->describe() + ": " + reason);
}

void Params::wrongType(const Property& p, const char* expected) const {
    fail(p, std::string("must be ") + expected + ", not <" + propertyTypeName(p.type) + ">");
}

Float Params::getFloat(const std::string& name, Float def) const {
    return has(name) ? getFloat(name) : def;
}

Float Params::getFloat(const std::string& name) const {
    const Property& p = require(name);
    if (p.type != PropertyType::Float && p.type != PropertyType::Integer) wrongType(p, "a <float>");
    if (!std::isfinite(Float(p.number))) fail(p, "is out of float range");
    return Float(p.number);
}

int Params::getInt(const std::string& name, int def) const {
    const Property* p = find(name);
    if (!p) return def;
    if (p->type != PropertyType::Integer) wrongType(*p, "an <integer>");
    if (p->integer < INT_MIN || p->integer > INT_MAX) fail(*p, "is out of the 32-bit range");
    return int(p->integer);
}

bool Params::getBool(const std::string& name, bool def) const {
    const Property* p = find(name);
    if (!p) return def;
    if (p->type != PropertyType::Boolean) wrongType(*p, "a <boolean>");
    return p->boolean;
}

std::string Params::getString(const std::string& name, const std::string& def) const {
    return has(name) ? getString(name) : def;
}

std::string Params::getString(const std::string& name) const {
    const Property& p = require(name);
    if (p.type != PropertyType::String) wrongType(p, "a <string>");
    return p.text;
}

Vec3f Params::getPoint(const std::string& name, Vec3f def) const {
    const Property* p = find(name);
    if (!p) return def;
    if (p->type != PropertyType::Point && p->type != PropertyType::Vector)
        wrongType(*p, "a <point> or <vector>");
    return p->vector;
}

Spectrum Params::getSpectrum(const std::string& name, Spectrum def) const {
    const Property* p = find(name);
    if (!p) return def;
    Spectrum s;
    if (p->type == PropertyType::Rgb || p->type == PropertyType::Spectrum)
        s = p->color;
    else if (p->type == PropertyType::Float || p->type == PropertyType::Integer)
        s = Spectrum(Float(p->number));
    else
        wrongType(*p, "an <rgb>, <spectrum> or <float>");
    if (!s.isValid()) fail(*p, "must be finite and non-negative");
    return s;
}

Transform Params::getTransform(const std::string& name) const {
    const Property* p = find(name);
    if (!p) return Transform();
    if (p->type != PropertyType::Transform) wrongType(*p, "a <transform>");
    return p->transform;
}

void Params::refuse(const std::string& name, const std::string& reason) const {
    if (const Property* p = find(name)) fail(*p, reason);
}

void Params::ignore(const std::string& name, std::vector<std::string>& warnings) const {
    if (const Property* p = find(name))
        warnings.push_back(p->where.file + ":" + std::to_string(p->where.line) + ": " +
                           object_->describe() + ": parameter '" + name +
                           "' is ignored (it does not affect caustica's output)");
}

std::vector<int> Params::takeChildren(const std::string& category) {
    std::vector<int> out;
    for (size_t i = 0; i < object_->children.size(); ++i) {
        const ChildRef& c = object_->children[i];
        if (desc_.objects[size_t(c.object)].category == category) {
            taken_[i] = true;
            out.push_back(c.object);
        }
    }
    return out;
}

void Params::finish(std::vector<std::string>& warnings) const {
    for (size_t i = 0; i < object_->children.size(); ++i) {
        if (taken_[i]) continue;
        const ChildRef& c = object_->children[i];
        const ObjectEntity& child = desc_.objects[size_t(c.object)];
        throw Error(c.where.file, c.where.line,
                    object_->describe() + " cannot contain a <" + child.category + "> (" +
                        child.describe() + ")");
    }
    for (const Property& p : object_->properties)
        if (!p.read)
            warnings.push_back(p.where.file + ":" + std::to_string(p.where.line) + ": " +
                               object_->describe() + ": parameter '" + p.name +
                               "' is not used (misspelt, or not supported by this plugin)");
}

}  // namespace caustica::mitsuba
