#include "caustica/scene/emitter_boxes.h"

#include <cmath>
#include <vector>

#include "caustica/scene/scene.h"

namespace caustica {

EmitterBoxes buildEmitterBoxes(const Scene& scene) {
    EmitterBoxes out;
    if (scene.environmentLight >= 0) return out;  // a ray that hits nothing finds emission
    std::vector<int32_t> slot(scene.shapes.size(), -1);
    for (size_t s = 0; s < scene.shapes.size(); ++s) {
        if (scene.shapes[s].light < 0) continue;
        if (out.count == EmitterBoxes::kMaxBoxes) return EmitterBoxes{};
        slot[s] = int32_t(out.count++);
    }
    if (out.count > 0) {
        const SceneView view = scene.view();
        const uint32_t prims = view.numPrimitives();
        for (uint32_t p = 0; p < prims; ++p) {
            const int32_t k = slot[view.shapeOf(p)];
            if (k >= 0) out.boxes[k].extend(scene.primitiveBounds(p));
        }
        const Bounds3f all = scene.bounds();
        const Float sceneSize = maxComponent(max(abs(all.lo), abs(all.hi))) + length(all.diagonal());
        uint32_t kept = 0;
        for (uint32_t k = 0; k < out.count; ++k) {
            Bounds3f b = out.boxes[k];
            if (b.empty()) continue;  // a shape without primitives: nothing to hit
            const Float pad = Float(1e-4) * length(b.diagonal()) + Float(1e-5) * sceneSize;
            b.lo = b.lo - Vec3f(pad);
            b.hi = b.hi + Vec3f(pad);
            if (!std::isfinite(b.lo.x + b.lo.y + b.lo.z + b.hi.x + b.hi.y + b.hi.z)) return EmitterBoxes{};
            out.boxes[kept++] = b;
        }
        out.count = kept;
    }
    out.usable = true;
    return out;
}

}  // namespace caustica
