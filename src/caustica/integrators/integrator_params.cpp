#include "caustica/integrators/integrator_params.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "caustica/util/error.h"

namespace caustica {
namespace {

bool fromCommandLine(const IntegratorParam& p) { return p.kind == IntegratorParam::Kind::Text; }

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

}  // namespace

IntegratorParams::IntegratorParams(const IntegratorSpec& spec, const std::vector<IntegratorParam>& overrides)
    : type_(spec.type), where_(spec.where) {
    for (const IntegratorParam& p : spec.params) {
        bool overridden = false;
        for (const IntegratorParam& o : overrides) overridden |= o.name == p.name;
        if (!overridden) params_.push_back(p);
    }
    params_.insert(params_.end(), overrides.begin(), overrides.end());
    read_.assign(params_.size(), false);
}

bool IntegratorParams::has(const std::string& name) const {
    for (const IntegratorParam& p : params_)
        if (p.name == name) return true;
    return false;
}

const IntegratorParam* IntegratorParams::take(const std::string& name) {
    for (size_t i = 0; i < params_.size(); ++i)
        if (params_[i].name == name) {
            read_[i] = true;
            return &params_[i];
        }
    return nullptr;
}

void IntegratorParams::fail(const std::string& name, const std::string& reason) const {
    for (const IntegratorParam& p : params_)
        if (p.name == name) {
            if (fromCommandLine(p)) throw Error(p.where + " " + p.text + ": " + reason);
            throw Error(p.where + ": integrator '" + type_ + "': parameter '" + name + "' " + reason);
        }
    throw Error((where_.empty() ? std::string() : where_ + ": ") + "integrator '" + type_ + "': " + reason);
}

int64_t IntegratorParams::getInt(const std::string& name, int64_t def, int64_t lo, int64_t hi,
                                 const std::string& outOfRange) {
    const IntegratorParam* p = take(name);
    if (!p) return def;
    if (!fromCommandLine(*p) && p->kind != IntegratorParam::Kind::Integer)
        fail(name, "must be an <integer>");
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(p->text.c_str(), &end, 10);
    if (end == p->text.c_str() || *end != '\0' || errno == ERANGE) fail(name, "must be a whole number");
    if (v < lo || v > hi) {
        if (!outOfRange.empty()) fail(name, outOfRange);
        if (hi == INT64_MAX || hi == INT32_MAX) fail(name, "must be >= " + std::to_string(lo));
        fail(name, "must be in " + std::to_string(lo) + ".." + std::to_string(hi));
    }
    return v;
}

double IntegratorParams::getFloat(const std::string& name, double def, double lo, double hi) {
    const IntegratorParam* p = take(name);
    if (!p) return def;
    if (!fromCommandLine(*p) && p->kind != IntegratorParam::Kind::Float && p->kind != IntegratorParam::Kind::Integer)
        fail(name, "must be a <float>");
    char* end = nullptr;
    const double v = std::strtod(p->text.c_str(), &end);
    if (end == p->text.c_str() || *end != '\0') fail(name, "must be a number");
    if (!std::isfinite(v) || v < lo || v > hi) fail(name, "must be a finite number in [" + number(lo) + ", " + number(hi) + "]");
    return v;
}

bool IntegratorParams::getBool(const std::string& name, bool def) {
    const IntegratorParam* p = take(name);
    if (!p) return def;
    if (!fromCommandLine(*p) && p->kind != IntegratorParam::Kind::Boolean) fail(name, "must be a <boolean>");
    if (p->text == "true") return true;
    if (p->text == "false") return false;
    fail(name, "must be true or false");
}

std::string IntegratorParams::getString(const std::string& name, const std::string& def,
                                        std::initializer_list<const char*> allowed) {
    const IntegratorParam* p = take(name);
    if (!p) return def;
    if (!fromCommandLine(*p) && p->kind != IntegratorParam::Kind::String) fail(name, "must be a <string>");
    std::string list;
    for (const char* a : allowed) {
        if (p->text == a) return p->text;
        list += (list.empty() ? "" : " or ") + std::string(a);
    }
    fail(name, "must be " + list + ", not '" + p->text + "'");
}

std::vector<std::string> IntegratorParams::unread() const {
    std::vector<std::string> warnings;
    for (size_t i = 0; i < params_.size(); ++i) {
        if (read_[i]) continue;
        if (fromCommandLine(params_[i]))
            warnings.push_back(params_[i].where + " is not an option of the " + type_ + " integrator; ignored");
        else
            warnings.push_back(params_[i].where + ": parameter '" + params_[i].name + "' of integrator '" + type_ +
                               "' is not read by it (misspelt?); ignored");
    }
    return warnings;
}

}  // namespace caustica
