// integrator_spec.h — the scene's <integrator> as written: its type and its parameters, untyped
// beyond what the file says. The scene knows no integrator's settings: each integrator reads its
// own from this (integrators/integrator_params.h) and from the command line.
#pragma once

#include <string>
#include <vector>

namespace caustica {

/// One parameter as written in the scene (<integer name="max_depth" value="8"/>) or on the
/// command line (--mlt-chains 64).
struct IntegratorParam {
    enum class Kind { Integer, Float, Boolean, String, Text };  // Text: command line, any type
    std::string name;   // the scene's name ("max_depth", "p_large")
    Kind kind = Kind::Text;
    std::string text;   // the value as written ("8", "0.1", "true", "relative")
    std::string where;  // "scene.xml:12" for the scene, the option ("--mlt-chains") for the CLI
};

struct IntegratorSpec {
    std::string type = "path";  // the integrator that runs (io maps other Mitsuba types to it)
    std::string where;          // "scene.xml:12" of the <integrator>; "" without one
    std::vector<IntegratorParam> params;
    /// Mitsuba's aov integrator around this one: its `aovs` list as written ("dd.y:depth,
    /// nn:sh_normal"; film/aov_layers.h) and where ("scene.xml:3"); "" without one.
    std::string aovs, aovsWhere;
};

}  // namespace caustica
