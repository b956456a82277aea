// lane.h — the operations shading code is written in when it is generic over a lane type F:
//   F = float   one path: GPU threads, and scalar host code
//   F = Float4  four paths side by side (util/float4.h): an SSE register on the host
// MaskOf<F> is what comparing two F gives (bool, Mask4). Code written once over F with
// lane::select in place of branches on values gives each lane of a Float4 the bits the float
// instantiation gives that lane's inputs, because every operation here rounds as its scalar form.
#pragma once

#include <cmath>

#include "caustica/util/float4.h"
#include "caustica/util/platform.h"

namespace caustica {

template <class F>
struct LaneTraits {};  // not a lane type
template <>
struct LaneTraits<float> {
    using Mask = bool;
    static constexpr int width = 1;
};
template <>
struct LaneTraits<Float4> {
    using Mask = Mask4;
    static constexpr int width = 4;
};
template <class F>
using MaskOf = typename LaneTraits<F>::Mask;
/// The form of a per-path struct T for the lane type F: T itself for F = float; for F = Float4
/// the struct of four T side by side that the header defining it names by specialising
/// LaneForm4<T> (Spectrum -> SpectrumF4, LightSample -> LightSampleF4, BsdfSample -> BsdfSampleF4).
template <class T>
struct LaneForm4;
template <class T, class F>
struct LaneFormOf {
    static_assert(LaneTraits<F>::width == 1);
    using Type = T;
};
template <class T>
struct LaneFormOf<T, Float4> {
    using Type = typename LaneForm4<T>::Type;
};
template <class T, class F>
using LaneOf = typename LaneFormOf<T, F>::Type;

/// float or Float4: what generic functions that deduce F accept (so that a call with ints or
/// doubles still takes a function's float form).
template <class F>
concept LaneFloat = requires { typename LaneTraits<F>::Mask; };

namespace lane {

/// `f` in every lane of an F.
template <class F>
CA_HD_FORCE_INLINE F splat(float f) {
    if constexpr (LaneTraits<F>::width == 1)
        return f;
    else
        return F::broadcast(f);
}

/// A mask with every lane false.
template <class F>
CA_HD_FORCE_INLINE MaskOf<F> none() {
    return splat<F>(0) != splat<F>(0);
}

/// Four per-path flags as a Mask4, lane k = b[k].
CA_HD_FORCE_INLINE Mask4 maskOf(const bool (&b)[4]) {
    return Float4::fromLanes(b[0] ? 1.0f : 0.0f, b[1] ? 1.0f : 0.0f, b[2] ? 1.0f : 0.0f, b[3] ? 1.0f : 0.0f) > 0.0f;
}

// ---- F = float: the plain expressions (min/max as caustica::min/max).
CA_HD_FORCE_INLINE float select(bool m, float a, float b) { return m ? a : b; }
CA_HD_FORCE_INLINE bool any(bool m) { return m; }
CA_HD_FORCE_INLINE bool all(bool m) { return m; }
CA_HD_FORCE_INLINE float sqrt(float a) { return std::sqrt(a); }
CA_HD_FORCE_INLINE float abs(float a) { return std::fabs(a); }
CA_HD_FORCE_INLINE float copysign(float mag, float sign) { return std::copysign(mag, sign); }
CA_HD_FORCE_INLINE float min(float a, float b) { return a < b ? a : b; }
CA_HD_FORCE_INLINE float max(float a, float b) { return a > b ? a : b; }
CA_HD_FORCE_INLINE bool isInf(float a) { return std::fabs(a) == INFINITY; }
CA_HD_FORCE_INLINE bool isFinite(float a) { return std::fabs(a) < INFINITY; }  // std::isfinite

// ---- F = Float4.
CA_HD_FORCE_INLINE Float4 select(Mask4 m, Float4 a, Float4 b) { return Float4::select(m, a, b); }
CA_HD_FORCE_INLINE bool any(Mask4 m) { return m.bits() != 0; }
CA_HD_FORCE_INLINE bool all(Mask4 m) { return m.bits() == 0xfu; }
CA_HD_FORCE_INLINE Float4 sqrt(Float4 a) { return Float4::sqrt(a); }
CA_HD_FORCE_INLINE Float4 abs(Float4 a) { return Float4::abs(a); }
CA_HD_FORCE_INLINE Float4 copysign(Float4 mag, Float4 sign) { return Float4::copysign(mag, sign); }
CA_HD_FORCE_INLINE Float4 min(Float4 a, Float4 b) { return Float4::minimum(a, b); }
CA_HD_FORCE_INLINE Float4 max(Float4 a, Float4 b) { return Float4::maximum(a, b); }
CA_HD_FORCE_INLINE Mask4 isInf(Float4 a) { return Float4::abs(a) == INFINITY; }
CA_HD_FORCE_INLINE Mask4 isFinite(Float4 a) { return Float4::abs(a) < INFINITY; }

/// sqrt(max(v, 0)), as caustica::safeSqrt.
template <class F>
CA_HD_FORCE_INLINE F safeSqrt(F v) {
    return lane::sqrt(lane::max(v, splat<F>(0)));
}

}  // namespace lane
}  // namespace caustica
