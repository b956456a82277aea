#include "caustica/integrators/whitted/whitted_settings.h"

namespace caustica {

const std::vector<IntegratorOption>& whittedOptions() {
    static const std::vector<IntegratorOption> options = {
        {"--whitted-max-depth", "max_depth",
         "whitted: longest path in ray segments, -1 = unbounded (default -1; 2 = direct light "
         "only)"},
        {"--whitted-rr-depth", "rr_depth",
         "whitted: Russian roulette on specular branches from this depth (default 5)"},
        {"--whitted-hide-emitters", "hide_emitters",
         "whitted: emitters seen directly by the camera render black, true/false (default false)"},
    };
    return options;
}

}  // namespace caustica
