// point_extent.h — the bounding box and the largest radius of a PointSet, computed where the
// points live (single source, launch.h). Min and max are exact, so both are deterministic.
#pragma once

#include <cstddef>
#include <vector>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/spatial/point_set.h"

namespace caustica {
namespace spatial_detail {

/// Elements one work item of the bounds reduction folds.
inline constexpr size_t kBoundsBlock = 256;

/// out[b] = bounds of items [b * kBoundsBlock, (b + 1) * kBoundsBlock) (clipped to n); an item
/// is a Vec3f or a Bounds3f (Bounds3f::extend takes both).
template <class Exec, class Item>
void blockBounds(Exec exec, const Item* items, size_t n, Bounds3f* out) {
    const size_t blocks = (n + kBoundsBlock - 1) / kBoundsBlock;
    launch(
        exec, "spatial.bounds", blocks,
        [=] CA_HD(size_t b) {
            Bounds3f box;
            const size_t end = min(n, (b + 1) * kBoundsBlock);
            for (size_t i = b * kBoundsBlock; i < end; ++i) box.extend(items[i]);
            out[b] = box;
        },
        1);
}

}  // namespace spatial_detail

/// The bounding box of `positions` (memory of Exec's device); empty() when there are none.
/// Block-wise on the device until at most kBoundsBlock boxes remain, the rest on the host.
template <class Exec>
Bounds3f pointBounds(Exec exec, Span<const Vec3f> positions) {
    using namespace spatial_detail;
    Bounds3f total;
    if (positions.empty()) return total;
    size_t count = (positions.size() + kBoundsBlock - 1) / kBoundsBlock;
    Buffer<Bounds3f> partial(Exec::device(), count);
    blockBounds(exec, positions.data(), positions.size(), partial.data());
    while (count > kBoundsBlock) {
        const size_t next = (count + kBoundsBlock - 1) / kBoundsBlock;
        Buffer<Bounds3f> coarser(Exec::device(), next);
        blockBounds(exec, partial.data(), count, coarser.data());
        partial = std::move(coarser);
        count = next;
    }
    for (const Bounds3f& b : partial.toHost()) total.extend(b);
    return total;
}

/// The largest radius of `points` (0 when there are none, or all radii are 0).
template <class Exec>
Float maxRadius(Exec, const PointSet& points) {
    if (points.radii.empty()) return points.size() > 0 ? max(points.radius, Float(0)) : Float(0);
    return max(reduceMax(Exec::device(), points.radii), Float(0));
}

}  // namespace caustica
