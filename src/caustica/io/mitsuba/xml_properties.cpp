#include "caustica/io/mitsuba/xml_properties.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "caustica/io/mesh/text_parse.h"
#include "caustica/io/mitsuba/spectrum_to_rgb.h"

namespace caustica::mitsuba {

namespace {

using meshio::quoteText;

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

/// value="x, y, z" (or one value for all three), or x/y/z attributes defaulting to `def`.
Vec3f xyzOrValue(const XmlFile& f, const pugi::xml_node& n, Float def, const std::string& what) {
    if (f.has(n, "value")) {
        if (f.has(n, "x") || f.has(n, "y") || f.has(n, "z"))
            f.fail(n, "<" + std::string(n.name()) + ">: give either 'value' or 'x'/'y'/'z'");
        std::vector<double> v = f.numbers(n, f.attribute(n, "value"), what, {1, 3});
        return v.size() == 1 ? Vec3f(Float(v[0])) : Vec3f(Float(v[0]), Float(v[1]), Float(v[2]));
    }
    Vec3f out(def);
    const char* axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k)
        if (f.has(n, axes[k])) out[k] = Float(f.number(n, f.attribute(n, axes[k]), what));
    return out;
}

Vec3f threeNumbers(const XmlFile& f, const pugi::xml_node& n, const char* attr) {
    std::vector<double> v =
        f.numbers(n, f.required(n, attr), std::string(1, '\'') + attr + "' of <lookat>", {3});
    return {Float(v[0]), Float(v[1]), Float(v[2])};
}

Transform lookAtOp(const XmlFile& f, const pugi::xml_node& n) {
    f.checkAttributes(n, {"origin", "target", "up"});
    Vec3f origin = threeNumbers(f, n, "origin"), target = threeNumbers(f, n, "target");
    Vec3f up = f.has(n, "up") ? threeNumbers(f, n, "up") : Vec3f(0);
    if (lengthSquared(target - origin) == 0) f.fail(n, "<lookat>: origin and target coincide");
    // Mitsuba: a missing or zero `up` becomes any vector perpendicular to the view direction.
    if (lengthSquared(up) == 0) up = Frame(normalize(target - origin)).s;
    if (lengthSquared(cross(up, target - origin)) == 0)
        f.fail(n, "<lookat>: 'up' is parallel to the view direction");
    return lookAt(origin, target, up);
}

Transform transformOp(const XmlFile& f, const pugi::xml_node& n) {
    const std::string tag = n.name();
    if (tag == "translate") {
        f.checkAttributes(n, {"value", "x", "y", "z"});
        return translate(xyzOrValue(f, n, 0, "<translate>"));
    }
    if (tag == "scale") {
        f.checkAttributes(n, {"value", "x", "y", "z"});
        Vec3f s = xyzOrValue(f, n, 1, "<scale>");
        if (s.x == 0 || s.y == 0 || s.z == 0)
            f.fail(n, "<scale> by zero makes the transform singular");
        return scale(s);
    }
    if (tag == "rotate") {
        f.checkAttributes(n, {"value", "x", "y", "z", "angle"});
        Vec3f axis = xyzOrValue(f, n, 0, "<rotate> axis");
        Float angle = Float(f.number(n, f.required(n, "angle"), "'angle' of <rotate>"));
        if (lengthSquared(axis) == 0)
            f.fail(n, "<rotate> needs a non-zero axis (x, y, z or value)");
        return rotate(axis, angle);
    }
    if (tag == "matrix") {
        f.checkAttributes(n, {"value"});
        std::vector<double> v = f.numbers(n, f.required(n, "value"), "<matrix>", {16, 9});
        Matrix4 m;
        const int dim = v.size() == 16 ? 4 : 3;
        for (int r = 0; r < dim; ++r)
            for (int c = 0; c < dim; ++c) m.m[r][c] = Float(v[size_t(r * dim + c)]);
        Matrix4 inv;
        if (!invert(m, inv)) f.fail(n, "<matrix> is singular (not invertible)");
        return {m, inv};
    }
    if (tag == "lookat") return lookAtOp(f, n);
    if (tag == "lookAt") f.fail(n, "<lookAt> is Mitsuba 0.6 syntax; Mitsuba 3 writes <lookat>");
    f.fail(n, "<transform> can contain only translate, rotate, scale, matrix and lookat, not <" +
                  tag + ">");
}

bool finiteMatrix(const Matrix4& m) {
    for (const auto& row : m.m)
        for (Float v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

/// Mitsuba's conversion depends on where the spectrum is used: emitters (radiance, intensity)
/// are not weighted by D65 nor clamped to 1; conductor eta/k are not clamped to 1.
SpectrumUse spectrumUse(const std::string& category, const std::string& name) {
    if (category == "emitter") return SpectrumUse::Emission;
    if (name == "eta" || name == "k") return SpectrumUse::Unbounded;
    return SpectrumUse::Reflectance;
}

/// <spectrum value="x"> or value="λ1:v1, λ2:v2, ..." (nm, increasing, at least two pairs,
/// separated by commas and/or blanks), converted to linear RGB as Mitsuba 3's RGB variants do.
Spectrum spectrumValue(const XmlFile& f, const pugi::xml_node& n, SpectrumUse use) {
    f.checkAttributes(n, {"name", "value", "filename"});
    if (f.has(n, "filename"))
        f.fail(n, "<spectrum filename=...> (measured spectra from files) is not supported; give "
                  "the values as wavelength:value pairs");
    const std::string value = f.required(n, "value");
    std::vector<std::string_view> tok = meshio::tokenize(value);
    if (tok.size() == 1 && value.find(':') == std::string::npos) {
        const double v = f.number(n, tok[0], "<spectrum> value");
        if (v < 0) f.fail(n, "<spectrum> value must be non-negative");
        return uniformSpectrumToRgb(v, use);
    }
    std::vector<double> wl, values;
    std::string_view previous;
    for (std::string_view t : tok) {
        std::vector<std::string_view> pair = meshio::tokenize(t, ":");
        if (pair.size() != 2 || t.front() == ':' || t.back() == ':' ||
            std::count(t.begin(), t.end(), ':') != 1)
            f.fail(n, "<spectrum>: cannot read " + quoteText(std::string(t)) +
                          " as a wavelength:value pair");
        const double w = f.number(n, pair[0], "<spectrum> wavelength");
        const double v = f.number(n, pair[1], "<spectrum> value");
        if (v < 0)
            f.fail(n, "<spectrum>: value " + quoteText(std::string(pair[1])) + " at " +
                          quoteText(std::string(pair[0])) + " nm must be non-negative");
        if (!wl.empty() && !(w > wl.back()))
            f.fail(n, "<spectrum>: wavelengths must increase (" + quoteText(std::string(pair[0])) +
                          " nm follows " + quoteText(std::string(previous)) + " nm)");
        previous = pair[0];
        wl.push_back(w);
        values.push_back(v);
    }
    if (wl.size() < 2) f.fail(n, "<spectrum> needs at least two wavelength:value pairs");
    return spectrumListToRgb(wl, values, use);
}

}  // namespace

bool isPropertyTag(std::string_view tag) {
    return tag == "float" || tag == "integer" || tag == "boolean" || tag == "string" ||
           tag == "point" || tag == "vector" || tag == "rgb" || tag == "spectrum" ||
           tag == "transform";
}

const char* propertyTypeName(PropertyType type) {
    static const char* kNames[] = {"float",  "integer", "boolean",  "string",   "point",
                                   "vector", "rgb",     "spectrum", "transform"};
    return kNames[int(type)];
}

Transform parseTransform(const XmlFile& f, const pugi::xml_node& node) {
    Transform t;
    for (pugi::xml_node op : node.children()) {
        if (op.type() != pugi::node_element) {
            if (op.type() == pugi::node_pcdata || op.type() == pugi::node_cdata)
                f.fail(node, "unexpected text inside <transform>");
            continue;
        }
        Transform step;
        try {
            step = transformOp(f, op);
        } catch (const std::domain_error& e) {
            f.fail(op, std::string("<") + op.name() + ">: " + e.what());
        }
        t = step * t;
        if (!finiteMatrix(t.m) || !finiteMatrix(t.mInv))
            f.fail(op, "transform overflows (NaN or infinite entries) after <" +
                           std::string(op.name()) + ">");
    }
    return t;
}

Property parseProperty(const XmlFile& f, const pugi::xml_node& n, const std::string& category) {
    const std::string tag = n.name();
    Property p;
    p.where = f.where(n);
    p.name = f.required(n, "name");
    const std::string what = "<" + tag + " name=\"" + p.name + "\">";
    if (tag == "float") {
        f.checkAttributes(n, {"name", "value"});
        p.type = PropertyType::Float;
        p.number = f.number(n, f.required(n, "value"), what);
    } else if (tag == "integer") {
        f.checkAttributes(n, {"name", "value"});
        p.type = PropertyType::Integer;
        std::string v = f.required(n, "value");
        if (!meshio::parseInt64(v, p.integer))
            f.fail(n, "cannot read " + quoteText(v) + " as an integer (" + what + ")");
        p.number = double(p.integer);
    } else if (tag == "boolean") {
        f.checkAttributes(n, {"name", "value"});
        p.type = PropertyType::Boolean;
        std::string v = lower(f.required(n, "value"));
        if (v != "true" && v != "false")
            f.fail(n, what + " must be 'true' or 'false', not " + quoteText(v));
        p.boolean = v == "true";
    } else if (tag == "string") {
        f.checkAttributes(n, {"name", "value"});
        p.type = PropertyType::String;
        if (!f.has(n, "value")) f.fail(n, what + " needs a 'value' attribute");
        p.text = f.attribute(n, "value");
    } else if (tag == "point" || tag == "vector") {
        f.checkAttributes(n, {"name", "value", "x", "y", "z"});
        p.type = tag == "point" ? PropertyType::Point : PropertyType::Vector;
        if (!f.has(n, "value") && !(f.has(n, "x") && f.has(n, "y") && f.has(n, "z")))
            f.fail(n, what + " needs 'value' or all of 'x', 'y', 'z'");
        p.vector = xyzOrValue(f, n, 0, what);
    } else if (tag == "rgb") {
        f.checkAttributes(n, {"name", "value"});
        p.type = PropertyType::Rgb;
        std::vector<double> v = f.numbers(n, f.required(n, "value"), what, {1, 3});
        p.color =
            v.size() == 1 ? Spectrum(Float(v[0])) : Spectrum(Float(v[0]), Float(v[1]), Float(v[2]));
        // Mitsuba makes an <rgb> a bounded sRGB reflectance wherever <spectrum> is a reflectance
        // (negative values are refused where the value is read: Params::getSpectrum).
        if (spectrumUse(category, p.name) == SpectrumUse::Reflectance && p.color.maxValue() > 1)
            f.fail(n, "parameter '" + p.name +
                          "' must lie in [0, 1]: it is an <rgb> reflectance (Mitsuba refuses it too)");
    } else if (tag == "spectrum") {
        p.type = PropertyType::Spectrum;
        p.color = spectrumValue(f, n, spectrumUse(category, p.name));
    } else if (tag == "transform") {
        f.checkAttributes(n, {"name"});
        p.type = PropertyType::Transform;
        p.transform = parseTransform(f, n);
    } else {
        f.fail(n, "internal: <" + tag + "> is not a property");
    }
    if (tag != "transform") {
        for (pugi::xml_node c : n.children())
            if (c.type() == pugi::node_element || c.type() == pugi::node_pcdata)
                f.fail(n, what + " cannot have content");
    }
    return p;
}

}  // namespace caustica::mitsuba
