// integrator_params.h — how an integrator reads its settings: from the scene's <integrator>
// parameters, overridden by the command line's, typed, range-checked, marked read. Errors are one
// line naming where the value came from ("scene.xml:4: integrator 'direct': parameter
// 'emitter_samples' must be >= 0", "--mlt-large-step 2: must be in [0, 1]"); parameters nobody
// read become warnings (a misspelt name).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "caustica/scene/integrator_spec.h"

namespace caustica {

/// A command-line option that sets one of an integrator's parameters: `--mlt-chains 64` is the
/// parameter "chains" with the text "64" (and the same checks as in a scene).
struct IntegratorOption {
    const char* flag;   // "--mlt-chains"
    const char* param;  // "chains"
    const char* help;
};

class IntegratorParams {
public:
    /// `overrides` (the command line's) take the place of the scene's parameters of the same name.
    IntegratorParams(const IntegratorSpec& spec, const std::vector<IntegratorParam>& overrides = {});

    bool has(const std::string& name) const;
    /// A whole number in [lo, hi]; outside, the error says `outOfRange` (default: the bounds).
    int64_t getInt(const std::string& name, int64_t def, int64_t lo, int64_t hi, const std::string& outOfRange = "");
    /// A finite number in [lo, hi] (an <integer> is a number too).
    double getFloat(const std::string& name, double def, double lo, double hi);
    bool getBool(const std::string& name, bool def);
    /// One of `allowed`.
    std::string getString(const std::string& name, const std::string& def, std::initializer_list<const char*> allowed);

    /// Throws caustica::Error naming where `name` came from (the <integrator> for a name not
    /// given, e.g. "", for a reason about several parameters).
    [[noreturn]] void fail(const std::string& name, const std::string& reason) const;
    /// Warnings for the parameters given but never read.
    std::vector<std::string> unread() const;
    const std::string& type() const { return type_; }

private:
    const IntegratorParam* take(const std::string& name);

    std::string type_, where_;
    std::vector<IntegratorParam> params_;
    std::vector<bool> read_;
};

}  // namespace caustica
