// bsdf_more_util.h — builders of composite BSDF trees (blendbsdf, mask, twosided, null) for the
// tests of bsdf_composite.h (test helper, host only). Children are appended before their parent.
#pragma once

#include <vector>

#include "caustica/scene/bsdf.h"

namespace caustica::test {

inline uint32_t append(std::vector<Bsdf>& bsdfs, const Bsdf& b) {
    bsdfs.push_back(b);
    return uint32_t(bsdfs.size() - 1);
}

inline uint32_t blendOf(std::vector<Bsdf>& bsdfs, Float weight, uint32_t first, uint32_t second) {
    Bsdf b;
    b.type = BsdfType::Blend;
    b.weight = weight;
    b.front = first;
    b.back = second;
    return append(bsdfs, b);
}

/// blendbsdf(weight, first, second) of two new leaves.
inline uint32_t blend(std::vector<Bsdf>& bsdfs, Float weight, const Bsdf& first,
                      const Bsdf& second) {
    const uint32_t a = append(bsdfs, first), b = append(bsdfs, second);
    return blendOf(bsdfs, weight, a, b);
}

inline uint32_t maskOf(std::vector<Bsdf>& bsdfs, Float opacity, uint32_t nested) {
    Bsdf b;
    b.type = BsdfType::Mask;
    b.weight = opacity;
    b.front = nested;
    return append(bsdfs, b);
}

inline uint32_t mask(std::vector<Bsdf>& bsdfs, Float opacity, const Bsdf& nested) {
    return maskOf(bsdfs, opacity, append(bsdfs, nested));
}

inline uint32_t twoSidedOf(std::vector<Bsdf>& bsdfs, uint32_t front, uint32_t back) {
    Bsdf b;
    b.type = BsdfType::TwoSided;
    b.front = front;
    b.back = back;
    return append(bsdfs, b);
}

inline Bsdf nullBsdf() {
    Bsdf b;
    b.type = BsdfType::Null;
    return b;
}

}  // namespace caustica::test
