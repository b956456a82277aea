// pass_driver.cpp — what the pass drivers share that is not kernel code (pass_driver.h).
#include "caustica/integrators/pass_driver.h"

#include "caustica/accel/intersector.h"
#include "caustica/util/rng.h"

namespace caustica {

size_t wavefrontBytesPerPath() {
    return sizeof(PathState) + sizeof(IndependentSampler) + sizeof(Hit) + sizeof(ShadowRay) + 6 * sizeof(uint32_t);
}

}  // namespace caustica
