// params.h — how builders read an entity's parameters: by name, with defaults, typed, and marked
// as read. Anything given but never read becomes a warning (a misspelt name); nested objects the
// builder does not take are errors. Errors name the file and the line of the offending element.
#pragma once

#include <string>
#include <vector>

#include "caustica/io/mitsuba/xml_entities.h"

namespace caustica::mitsuba {

class Params {
public:
    Params(const SceneDescription& desc, int object);

    const ObjectEntity& object() const { return *object_; }
    const SceneDescription& description() const { return desc_; }

    bool has(const std::string& name) const;
    /// The property (marked read) or nullptr.
    const Property* find(const std::string& name) const;

    Float getFloat(const std::string& name, Float def) const;
    Float getFloat(const std::string& name) const;  // required
    int getInt(const std::string& name, int def) const;
    bool getBool(const std::string& name, bool def) const;
    std::string getString(const std::string& name, const std::string& def) const;
    std::string getString(const std::string& name) const;      // required
    Vec3f getPoint(const std::string& name, Vec3f def) const;  // <point> or <vector>
    /// <rgb>, <spectrum> or <float>; refuses NaN/Inf and negative components.
    Spectrum getSpectrum(const std::string& name, Spectrum def) const;
    Transform getTransform(const std::string& name) const;  // identity when absent

    /// Errors if `name` is given: for Mitsuba parameters that caustica cannot honour yet.
    void refuse(const std::string& name, const std::string& reason) const;
    /// Marks `name` as read and warns that it is ignored (it does not change the image).
    void ignore(const std::string& name, std::vector<std::string>& warnings) const;

    /// Takes the nested or referenced objects of `category` (e.g. "bsdf"), in document order.
    std::vector<int> takeChildren(const std::string& category);

    /// Errors for nested objects nobody took; warnings for parameters nobody read.
    void finish(std::vector<std::string>& warnings) const;

    [[noreturn]] void fail(const std::string& reason) const;
    [[noreturn]] void fail(const Property& at, const std::string& reason) const;
    [[noreturn]] void failAtChild(int childObject, const std::string& reason) const;

private:
    const Property& require(const std::string& name) const;
    [[noreturn]] void wrongType(const Property& p, const char* expected) const;

    const SceneDescription& desc_;
    const ObjectEntity* object_;
    std::vector<bool> taken_;
};

}  // namespace caustica::mitsuba
