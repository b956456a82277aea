// ball_range.h — the distance test of a ball query over a contiguous range of positions (a grid
// row's points in cell order): f(k) for every k in [begin, end) with inBall(positions[k], center,
// radius), ascending k. On a CPU the range is tested in blocks of kBallBlock positions without a
// branch per candidate (about half of a row's candidates are inside, so a branch per candidate
// is mispredicted about half the time): each block gives a bit mask of the positions inside, and
// f runs only for its set bits. Same predicate (inBall), same order: the same results to the bit.
// A GPU thread tests one candidate at a time (its warp diverges on f anyway).
#pragma once

#include <bit>
#include <cstdint>

#include "caustica/spatial/point_set.h"

namespace caustica {

inline constexpr uint32_t kBallBlock = 8;

template <class F>
CA_HD_INLINE void forEachInBallRange(const Vec3f* positions, uint32_t begin, uint32_t end, Vec3f center,
                                     Float radius, F& f) {
#if CA_GPU_CODE
    for (uint32_t k = begin; k < end; ++k)
        if (inBall(positions[k], center, radius)) f(k);
#else
    uint32_t k = begin;
    for (; k + kBallBlock <= end; k += kBallBlock) {
        uint32_t mask = 0;
        for (uint32_t j = 0; j < kBallBlock; ++j) mask |= uint32_t(inBall(positions[k + j], center, radius)) << j;
        while (mask) {
            f(k + uint32_t(std::countr_zero(mask)));
            mask &= mask - 1;
        }
    }
    for (; k < end; ++k)
        if (inBall(positions[k], center, radius)) f(k);
#endif
}

}  // namespace caustica
