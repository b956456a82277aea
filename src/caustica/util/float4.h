// float4.h — four floats side by side, one source for CPU and GPU:
//   Float4  an SSE register on the host, a plain array in GPU code (and on hosts without SSE2),
//           where its loops become scalar code
//   Mask4   the result of comparing two Float4: four lanes, each all-ones or zero
// The BVH traversal tests four boxes at once with it; the shading code written over a lane type
// (lane.h) runs four paths at once with it. Every operation rounds exactly like the scalar
// expression it stands for (min/max follow caustica::min/max, including which operand a NaN
// yields; no fused multiply-add), so code run on Float4 gives each lane the bits the scalar code
// gives that lane's inputs.
#pragma once

#include <cmath>
#include <cstdint>

#include "caustica/util/platform.h"

#if !defined(__CUDA_ARCH__) && (defined(__SSE2__) || defined(_M_X64))
#define CA_FLOAT4_SSE 1
#include <emmintrin.h>
#else
#define CA_FLOAT4_SSE 0
#endif

namespace caustica {

#if CA_FLOAT4_SSE

struct Mask4 {
    __m128 v;  // per lane all-ones (true) or zero (false)

    /// Bit k set where lane k is true.
    uint32_t bits() const { return uint32_t(_mm_movemask_ps(v)); }
    friend Mask4 operator&(Mask4 a, Mask4 b) { return {_mm_and_ps(a.v, b.v)}; }
    friend Mask4 operator|(Mask4 a, Mask4 b) { return {_mm_or_ps(a.v, b.v)}; }
    friend Mask4 operator!(Mask4 a) { return {_mm_xor_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(-1)))}; }
};

/// Four floats with element-wise operations.
struct Float4 {
    __m128 v;

    static Float4 load(const float* p) { return {_mm_load_ps(p)}; }  // p 16-byte aligned
    static Float4 loadUnaligned(const float* p) { return {_mm_loadu_ps(p)}; }
    static Float4 broadcast(float f) { return {_mm_set1_ps(f)}; }
    static Float4 fromLanes(float a, float b, float c, float d) { return {_mm_setr_ps(a, b, c, d)}; }
    void store(float* p) const { _mm_storeu_ps(p, v); }
    float operator[](int k) const {
        alignas(16) float f[4];
        _mm_store_ps(f, v);
        return f[k];
    }

    friend Float4 operator+(Float4 a, Float4 b) { return {_mm_add_ps(a.v, b.v)}; }
    friend Float4 operator-(Float4 a, Float4 b) { return {_mm_sub_ps(a.v, b.v)}; }
    friend Float4 operator*(Float4 a, Float4 b) { return {_mm_mul_ps(a.v, b.v)}; }
    friend Float4 operator/(Float4 a, Float4 b) { return {_mm_div_ps(a.v, b.v)}; }
    friend Float4 operator-(Float4 a) { return {_mm_xor_ps(a.v, _mm_set1_ps(-0.0f))}; }
    // minps/maxps return the second operand unless the comparison holds: a < b ? a : b.
    static Float4 minimum(Float4 a, Float4 b) { return {_mm_min_ps(a.v, b.v)}; }
    static Float4 maximum(Float4 a, Float4 b) { return {_mm_max_ps(a.v, b.v)}; }
    friend Float4 min(Float4 a, Float4 b) { return minimum(a, b); }
    friend Float4 max(Float4 a, Float4 b) { return maximum(a, b); }
    // Named as members, so that lane.h's functions of the same names can call them.
    static Float4 sqrt(Float4 a) { return {_mm_sqrt_ps(a.v)}; }
    static Float4 abs(Float4 a) { return {_mm_andnot_ps(_mm_set1_ps(-0.0f), a.v)}; }
    /// |mag| with the sign bit of `sign`, as std::copysign.
    static Float4 copysign(Float4 mag, Float4 sign) {
        const __m128 s = _mm_set1_ps(-0.0f);
        return {_mm_or_ps(_mm_andnot_ps(s, mag.v), _mm_and_ps(s, sign.v))};
    }
    /// Lane k of a where m is true, of b where not.
    static Float4 select(Mask4 m, Float4 a, Float4 b) {
        return {_mm_or_ps(_mm_and_ps(m.v, a.v), _mm_andnot_ps(m.v, b.v))};
    }

    // Comparisons as IEEE's: false where a lane is NaN (true for !=).
    friend Mask4 operator<(Float4 a, Float4 b) { return {_mm_cmplt_ps(a.v, b.v)}; }
    friend Mask4 operator<=(Float4 a, Float4 b) { return {_mm_cmple_ps(a.v, b.v)}; }
    friend Mask4 operator>(Float4 a, Float4 b) { return {_mm_cmpgt_ps(a.v, b.v)}; }
    friend Mask4 operator>=(Float4 a, Float4 b) { return {_mm_cmpge_ps(a.v, b.v)}; }
    friend Mask4 operator==(Float4 a, Float4 b) { return {_mm_cmpeq_ps(a.v, b.v)}; }
    friend Mask4 operator!=(Float4 a, Float4 b) { return {_mm_cmpneq_ps(a.v, b.v)}; }
    /// Bit k set where a[k] <= b[k] (false for NaN).
    friend uint32_t lessEqualMask(Float4 a, Float4 b) { return uint32_t(_mm_movemask_ps(_mm_cmple_ps(a.v, b.v))); }
};

#else

struct Mask4 {
    bool m[4];

    CA_HD_FORCE_INLINE uint32_t bits() const {
        return uint32_t(m[0]) | uint32_t(m[1]) << 1 | uint32_t(m[2]) << 2 | uint32_t(m[3]) << 3;
    }
    CA_HD_FORCE_INLINE friend Mask4 operator&(Mask4 a, Mask4 b) {
        return {{a.m[0] && b.m[0], a.m[1] && b.m[1], a.m[2] && b.m[2], a.m[3] && b.m[3]}};
    }
    CA_HD_FORCE_INLINE friend Mask4 operator|(Mask4 a, Mask4 b) {
        return {{a.m[0] || b.m[0], a.m[1] || b.m[1], a.m[2] || b.m[2], a.m[3] || b.m[3]}};
    }
    CA_HD_FORCE_INLINE friend Mask4 operator!(Mask4 a) { return {{!a.m[0], !a.m[1], !a.m[2], !a.m[3]}}; }
};

struct Float4 {
    float v[4];

    CA_HD_FORCE_INLINE static Float4 load(const float* p) { return {{p[0], p[1], p[2], p[3]}}; }
    CA_HD_FORCE_INLINE static Float4 loadUnaligned(const float* p) { return load(p); }
    CA_HD_FORCE_INLINE static Float4 broadcast(float f) { return {{f, f, f, f}}; }
    CA_HD_FORCE_INLINE static Float4 fromLanes(float a, float b, float c, float d) { return {{a, b, c, d}}; }
    CA_HD_FORCE_INLINE void store(float* p) const {
        for (int k = 0; k < 4; ++k) p[k] = v[k];
    }
    CA_HD_FORCE_INLINE float operator[](int k) const { return v[k]; }
    template <class Op>
    CA_HD_FORCE_INLINE static Float4 map(Float4 a, Float4 b, Op op) {
        Float4 r;
        for (int k = 0; k < 4; ++k) r.v[k] = op(a.v[k], b.v[k]);
        return r;
    }
    template <class Op>
    CA_HD_FORCE_INLINE static Mask4 compare(Float4 a, Float4 b, Op op) {
        Mask4 r;
        for (int k = 0; k < 4; ++k) r.m[k] = op(a.v[k], b.v[k]);
        return r;
    }
    CA_HD_FORCE_INLINE friend Float4 operator+(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x + y; });
    }
    CA_HD_FORCE_INLINE friend Float4 operator-(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x - y; });
    }
    CA_HD_FORCE_INLINE friend Float4 operator*(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x * y; });
    }
    CA_HD_FORCE_INLINE friend Float4 operator/(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x / y; });
    }
    CA_HD_FORCE_INLINE friend Float4 operator-(Float4 a) {
        return map(a, a, [](float x, float) { return -x; });
    }
    CA_HD_FORCE_INLINE static Float4 minimum(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x < y ? x : y; });
    }
    CA_HD_FORCE_INLINE static Float4 maximum(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x > y ? x : y; });
    }
    CA_HD_FORCE_INLINE friend Float4 min(Float4 a, Float4 b) { return minimum(a, b); }
    CA_HD_FORCE_INLINE friend Float4 max(Float4 a, Float4 b) { return maximum(a, b); }
    CA_HD_FORCE_INLINE static Float4 sqrt(Float4 a) {
        return map(a, a, [](float x, float) { return sqrtf(x); });
    }
    CA_HD_FORCE_INLINE static Float4 abs(Float4 a) {
        return map(a, a, [](float x, float) { return fabsf(x); });
    }
    CA_HD_FORCE_INLINE static Float4 copysign(Float4 mag, Float4 sign) {
        return map(mag, sign, [](float x, float y) { return copysignf(x, y); });
    }
    CA_HD_FORCE_INLINE static Float4 select(Mask4 m, Float4 a, Float4 b) {
        Float4 r;
        for (int k = 0; k < 4; ++k) r.v[k] = m.m[k] ? a.v[k] : b.v[k];
        return r;
    }
    CA_HD_FORCE_INLINE friend Mask4 operator<(Float4 a, Float4 b) {
        return compare(a, b, [](float x, float y) { return x < y; });
    }
    CA_HD_FORCE_INLINE friend Mask4 operator<=(Float4 a, Float4 b) {
        return compare(a, b, [](float x, float y) { return x <= y; });
    }
    CA_HD_FORCE_INLINE friend Mask4 operator>(Float4 a, Float4 b) {
        return compare(a, b, [](float x, float y) { return x > y; });
    }
    CA_HD_FORCE_INLINE friend Mask4 operator>=(Float4 a, Float4 b) {
        return compare(a, b, [](float x, float y) { return x >= y; });
    }
    CA_HD_FORCE_INLINE friend Mask4 operator==(Float4 a, Float4 b) {
        return compare(a, b, [](float x, float y) { return x == y; });
    }
    CA_HD_FORCE_INLINE friend Mask4 operator!=(Float4 a, Float4 b) {
        return compare(a, b, [](float x, float y) { return x != y; });
    }
    CA_HD_FORCE_INLINE friend uint32_t lessEqualMask(Float4 a, Float4 b) { return (a <= b).bits(); }
};

#endif

// A scalar on either side stands for itself in all four lanes.
CA_HD_FORCE_INLINE Float4 operator+(Float4 a, float b) { return a + Float4::broadcast(b); }
CA_HD_FORCE_INLINE Float4 operator+(float a, Float4 b) { return Float4::broadcast(a) + b; }
CA_HD_FORCE_INLINE Float4 operator-(Float4 a, float b) { return a - Float4::broadcast(b); }
CA_HD_FORCE_INLINE Float4 operator-(float a, Float4 b) { return Float4::broadcast(a) - b; }
CA_HD_FORCE_INLINE Float4 operator*(Float4 a, float b) { return a * Float4::broadcast(b); }
CA_HD_FORCE_INLINE Float4 operator*(float a, Float4 b) { return Float4::broadcast(a) * b; }
CA_HD_FORCE_INLINE Float4 operator/(Float4 a, float b) { return a / Float4::broadcast(b); }
CA_HD_FORCE_INLINE Float4 operator/(float a, Float4 b) { return Float4::broadcast(a) / b; }
CA_HD_FORCE_INLINE Mask4 operator<(Float4 a, float b) { return a < Float4::broadcast(b); }
CA_HD_FORCE_INLINE Mask4 operator>(Float4 a, float b) { return a > Float4::broadcast(b); }
CA_HD_FORCE_INLINE Mask4 operator<=(Float4 a, float b) { return a <= Float4::broadcast(b); }
CA_HD_FORCE_INLINE Mask4 operator>=(Float4 a, float b) { return a >= Float4::broadcast(b); }
CA_HD_FORCE_INLINE Mask4 operator==(Float4 a, float b) { return a == Float4::broadcast(b); }

}  // namespace caustica
