// plugin_table.h — one table per object category mapping a plugin type ("diffuse", "obj", ...)
// to the function that builds it. Adding a plugin is one function and one table row.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "caustica/io/mitsuba/params.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

template <class BuildFn>
struct PluginTable {
    std::vector<std::pair<std::string, BuildFn>> entries;
    /// Known Mitsuba types that are refused with a specific reason (e.g. polarised BSDFs).
    std::vector<std::pair<std::string, std::string>> refusals = {};

    /// The builder for the entity's type, or an error listing the supported types.
    BuildFn find(const Params& params) const {
        const ObjectEntity& e = params.object();
        std::string known;
        for (const auto& [type, fn] : entries) {
            if (type == e.type) return fn;
            known += (known.empty() ? "" : ", ") + type;
        }
        std::string why;
        for (const auto& [type, reason] : refusals)
            if (type == e.type) why = ": " + reason;
        throw Error(e.where.file, e.where.line,
                    "unsupported " + e.category + " type '" + e.type + "'" + why +
                        " (supported: " + known + ")");
    }
};

}  // namespace caustica::mitsuba
