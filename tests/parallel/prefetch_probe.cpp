// prefetch_probe.cpp — compiled to assembly (not linked) by prefetch_codegen.cmake, which checks
// that the hit prefetches survive optimisation: prefetchVertices is made only of prefetches, and
// g++ -O3 once marked such a helper pure and deleted every call it did not inline
// (parallel/prefetch.h). The probe calls it the way the wavefront's shade stage does.
#include "caustica/integrators/hit_prefetch.h"

extern "C" void caustica_prefetch_probe(const caustica::SceneView& scene, const caustica::Hit& hit) {
    caustica::prefetchVertices(scene, hit);
}
