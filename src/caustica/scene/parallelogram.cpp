// parallelogram.cpp — see parallelogram.h.
#include "caustica/scene/parallelogram.h"

namespace caustica {

bool meshParallelogram(const Scene& scene, const Shape& shape, MeshParallelogram& out) {
    if (shape.type != ShapeType::Mesh || shape.primCount != 2) return false;
    const uint32_t ia = shape.primOffset, ib = shape.primOffset + 1;
    if (size_t(ib) >= scene.triangles.size()) return false;
    const Vec3u ta = scene.triangles[ia], tb = scene.triangles[ib];
    const Vec3f a[3] = {scene.positions[ta.x], scene.positions[ta.y], scene.positions[ta.z]};
    const Vec3f b[3] = {scene.positions[tb.x], scene.positions[tb.y], scene.positions[tb.z]};
    auto slotIn = [](const Vec3f (&tri)[3], Vec3f p) {
        for (int k = 0; k < 3; ++k)
            if (tri[k] == p) return k;
        return -1;
    };
    int notShared = -1, shared = 0;
    for (int k = 0; k < 3; ++k) {
        if (slotIn(b, a[k]) >= 0)
            ++shared;
        else
            notShared = k;
    }
    if (shared != 2 || notShared < 0) return false;
    const int k1 = (notShared + 1) % 3, k2 = (notShared + 2) % 3;
    const Vec3f corner = a[notShared], s1 = a[k1], s2 = a[k2];
    const int b1 = slotIn(b, s1), b2 = slotIn(b, s2);
    if (b1 < 0 || b2 < 0 || b1 == b2) return false;
    const int far = 3 - b1 - b2;
    const Vec3f opposite = b[far];
    // A parallelogram: the corners opposite the shared diagonal are symmetric about its middle.
    const double size = double(length(s1 - s2)) + double(length(s1 - corner)) + double(length(s2 - corner));
    const Vec3f gap = (corner + opposite) - (s1 + s2);
    if (!(size > 0) || !(double(length(gap)) <= 1e-6 * size)) return false;
    out.corner = corner;
    out.edgeU = s1 - corner;
    out.edgeV = s2 - corner;
    out.first = ia;
    out.second = ib;
    out.slots[0][0] = uint8_t(notShared), out.slots[0][1] = uint8_t(k1), out.slots[0][2] = uint8_t(k2);
    out.slots[1][0] = uint8_t(far), out.slots[1][1] = uint8_t(b1), out.slots[1][2] = uint8_t(b2);
    return true;
}

}  // namespace caustica
