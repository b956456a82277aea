#include "caustica/integrators/path/path_settings.h"

#include <climits>

namespace caustica {

PathSettings readPathSettings(IntegratorParams& p) {
    PathSettings s;
    s.maxDepth = int(p.getInt("max_depth", -1, -1, INT_MAX, "must be -1 (unbounded) or >= 0"));
    s.rrDepth = int(p.getInt("rr_depth", 5, 1, INT_MAX, "must be greater than zero"));
    s.hideEmitters = p.getBool("hide_emitters", false);
    return s;
}

}  // namespace caustica
