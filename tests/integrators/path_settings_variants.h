// path_settings_variants.h — the path tracer settings the bit-for-bit tests of its execution forms
// (wavefront_test.cpp, path_lanes_test.cpp) run: the defaults, max_depth 0, 1, 2 and 6 (with
// roulette from depth 1), hidden emitters.
#pragma once

#include <vector>

#include "caustica/integrators/path/path_kernel.h"

namespace caustica::test {

inline std::vector<PathSettings> pathSettingsVariants() {
    std::vector<PathSettings> v(6);
    v[1].maxDepth = 0;
    v[2].maxDepth = 1;
    v[3].maxDepth = 2;
    v[4].maxDepth = 6;
    v[4].rrDepth = 1;
    v[5].hideEmitters = true;
    return v;
}

}  // namespace caustica::test
