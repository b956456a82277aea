// math.h — small vector types and scalar helpers shared by CPU and GPU code.
#pragma once

#include <bit>
#include <cmath>
#include <type_traits>
#include <cstdint>

#include "caustica/util/lane.h"
#include "caustica/util/platform.h"

namespace caustica {

using Float = float;

inline constexpr Float kPi = 3.14159265358979323846f;
inline constexpr Float kInvPi = 0.31830988618379067154f;
inline constexpr Float kInv2Pi = 0.15915494309189533577f;
inline constexpr Float kInv4Pi = 0.07957747154594766788f;
inline constexpr Float kInfinity = 3.402823466e+38f;  // FLT_MAX: used as "no hit yet"
inline constexpr Float kOneMinusEpsilon = 0x1.fffffep-1f;

template <class T> CA_HD_INLINE T min(T a, T b) { return a < b ? a : b; }
template <class T> CA_HD_INLINE T max(T a, T b) { return a > b ? a : b; }
template <class T> CA_HD_INLINE T clamp(T v, T lo, T hi) { return v < lo ? lo : (v > hi ? hi : v); }
template <class T> CA_HD_INLINE T sqr(T v) { return v * v; }

/// n / d and n % d, with a 32-bit division whenever both fit in 32 bits (pixel and sample-slot
/// indices always do): the same result, at a fraction of a 64-bit division's cost on x86-64
/// before Ice Lake (Skylake: about 26 against 35-88 cycles, Agner Fog's instruction tables) and
/// on GPUs, which emulate 64-bit division. Two per camera sample were 2-4% of a glass-caustic
/// sample on this VM (docs/PERFORMANCE.md, 2026-11-26).
struct DivMod {
    uint64_t quot, rem;
};
CA_HD_INLINE DivMod divMod(uint64_t n, uint64_t d) {
    if (((n | d) >> 32) == 0) return {uint32_t(n) / uint32_t(d), uint32_t(n) % uint32_t(d)};
    return {n / d, n % d};
}
CA_HD_INLINE Float lerp(Float t, Float a, Float b) { return (1 - t) * a + t * b; }
CA_HD_INLINE Float safeSqrt(Float v) { return std::sqrt(max(v, Float(0))); }
CA_HD_INLINE Float radians(Float deg) { return deg * (kPi / 180); }
CA_HD_INLINE Float degrees(Float rad) { return rad * (180 / kPi); }

/// 2^x for x <= 0.5 (at least 2^-125), to about 2e-7 relative error, with no libm call (MLT's
/// small step computes one per perturbed coordinate; expf/logf/floor were about an eighth of its
/// time on the CPU). Integer part into the exponent; 2^f, |f| <= 1/2, by a degree-6 polynomial.
CA_HD_INLINE float exp2Approx(float x) {
    x = x < -125.0f ? -125.0f : x;
    const int i = int(x - 0.5f);  // truncation: ceil(x - 1/2) for x < 1/2, so f lies in (-1/2, 1/2]
    const float f = x - float(i);
    float p = 1.535336188e-4f;  // Horner, highest power first
    p = p * f + 0.001339887440f;
    p = p * f + 0.009618437358f;
    p = p * f + 0.05550332471f;
    p = p * f + 0.2402264791f;
    p = p * f + 0.6931472028f;
    p = p * f + 1.0f;
#ifdef __CUDA_ARCH__
    const float scale = __int_as_float((i + 127) << 23);
#else
    const float scale = std::bit_cast<float>(uint32_t(i + 127) << 23);
#endif
    return p * scale;
}

/// sin a and cos a for |a| <= π/4, by their Taylor polynomials to degree 9 and 10 (truncation
/// below 2e-9 there, so the float rounding of the evaluation dominates: within 2 ulp of the
/// correctly rounded values, tests/util/math_test.cpp). No range reduction and no libm call: the
/// concentric disk map (sampling.h), the warp of every diffuse bounce, takes its angle from this
/// range; sincosf and that warp were 5% of cornell-box's CPU time (sincosf alone 2.2%).
/// Generic over the lane type F (lane.h).
template <LaneFloat F>
CA_HD_INLINE void sinCosQuarterPi(F a, F& s, F& c) {
    const F a2 = a * a;
    F ps = lane::splat<F>(1.0f / 362880);  // Horner from the a^9 term down
    ps = ps * a2 - 1.0f / 5040;
    ps = ps * a2 + 1.0f / 120;
    ps = ps * a2 - 1.0f / 6;
    s = a + a * a2 * ps;
    F pc = lane::splat<F>(-1.0f / 3628800);
    pc = pc * a2 + 1.0f / 40320;
    pc = pc * a2 - 1.0f / 720;
    pc = pc * a2 + 1.0f / 24;
    pc = pc * a2 - 0.5f;
    c = 1.0f + a2 * pc;
}

/// sin 2πu and cos 2πu for any float u (samplers' u in [0, 1)): 4u is split exactly into the
/// nearest quarter turn k and a remainder in [-1/2, 1/2], whose angle sinCosQuarterPi takes; the
/// quarter turns swap and negate. No libm call (every φ = 2πu of the warps and BSDFs).
CA_HD_INLINE void sinCosTwoPi(float u, float& s, float& c) {
    const float v = 4 * u;
    const int k = v >= 0 ? int(v + 0.5f) : -int(0.5f - v);  // nearest integer (ties up)
    float sa, ca;
    sinCosQuarterPi((v - float(k)) * (kPi / 2), sa, ca);
    switch (k & 3) {
        case 0: s = sa; c = ca; break;
        case 1: s = ca; c = -sa; break;
        case 2: s = -sa; c = -ca; break;
        default: s = -ca; c = sa; break;
    }
}

struct Vec2f {
    Float x = 0, y = 0;
    constexpr Vec2f() = default;
    CA_HD constexpr Vec2f(Float x_, Float y_) : x(x_), y(y_) {}
    CA_HD Float operator[](int i) const { return i == 0 ? x : y; }
};
CA_HD_INLINE Vec2f operator+(Vec2f a, Vec2f b) { return {a.x + b.x, a.y + b.y}; }
CA_HD_INLINE Vec2f operator-(Vec2f a, Vec2f b) { return {a.x - b.x, a.y - b.y}; }
CA_HD_INLINE Vec2f operator*(Vec2f a, Float s) { return {a.x * s, a.y * s}; }
CA_HD_INLINE Vec2f operator*(Float s, Vec2f a) { return {a.x * s, a.y * s}; }

struct Vec3f {
    Float x = 0, y = 0, z = 0;
    constexpr Vec3f() = default;
    CA_HD constexpr Vec3f(Float x_, Float y_, Float z_) : x(x_), y(y_), z(z_) {}
    CA_HD explicit constexpr Vec3f(Float v) : x(v), y(v), z(v) {}
    CA_HD Float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    CA_HD Float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    CA_HD Vec3f& operator+=(Vec3f b) { x += b.x; y += b.y; z += b.z; return *this; }
    CA_HD Vec3f& operator-=(Vec3f b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
    CA_HD Vec3f& operator*=(Float s) { x *= s; y *= s; z *= s; return *this; }
};
CA_HD_INLINE Vec3f operator+(Vec3f a, Vec3f b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
CA_HD_INLINE Vec3f operator-(Vec3f a, Vec3f b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
CA_HD_INLINE Vec3f operator-(Vec3f a) { return {-a.x, -a.y, -a.z}; }
CA_HD_INLINE Vec3f operator*(Vec3f a, Float s) { return {a.x * s, a.y * s, a.z * s}; }
CA_HD_INLINE Vec3f operator*(Float s, Vec3f a) { return {a.x * s, a.y * s, a.z * s}; }
CA_HD_INLINE Vec3f operator*(Vec3f a, Vec3f b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
CA_HD_INLINE Vec3f operator/(Vec3f a, Float s) { Float inv = 1 / s; return a * inv; }
CA_HD_INLINE bool operator==(Vec3f a, Vec3f b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
CA_HD_INLINE Float dot(Vec3f a, Vec3f b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CA_HD_INLINE Float absDot(Vec3f a, Vec3f b) { return std::fabs(dot(a, b)); }
CA_HD_INLINE Vec3f cross(Vec3f a, Vec3f b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
CA_HD_INLINE Float lengthSquared(Vec3f a) { return dot(a, a); }
CA_HD_INLINE Float length(Vec3f a) { return std::sqrt(dot(a, a)); }
CA_HD_INLINE Vec3f normalize(Vec3f a) { return a / length(a); }
CA_HD_INLINE Vec3f min(Vec3f a, Vec3f b) { return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)}; }
CA_HD_INLINE Vec3f max(Vec3f a, Vec3f b) { return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)}; }
CA_HD_INLINE Vec3f abs(Vec3f a) { return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}; }
CA_HD_INLINE Float maxComponent(Vec3f a) { return max(a.x, max(a.y, a.z)); }
CA_HD_INLINE int maxDimension(Vec3f a) { return a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2); }
CA_HD_INLINE bool isFinite(Vec3f a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
/// Flips `v` so that it lies in the same hemisphere as `ref`.
CA_HD_INLINE Vec3f faceForward(Vec3f v, Vec3f ref) { return dot(v, ref) < 0 ? -v : v; }

struct Vec3u {
    uint32_t x = 0, y = 0, z = 0;
    CA_HD uint32_t operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

// ---- Vectors of lanes: the vectors of code generic over the lane type F (lane.h), Vec2Of<F> and
// Vec3Of<F>, are Vec2f and Vec3f for F = float and the structs below for Float4 (four vectors,
// coordinate by coordinate).
struct Vec2F4 {
    Float4 x, y;
};
struct Vec3F4 {
    Float4 x, y, z;
};
CA_HD_FORCE_INLINE Vec3F4 operator+(const Vec3F4& a, const Vec3F4& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
CA_HD_FORCE_INLINE Vec3F4 operator-(const Vec3F4& a, const Vec3F4& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
CA_HD_FORCE_INLINE Vec3F4 operator-(const Vec3F4& a) { return {-a.x, -a.y, -a.z}; }
CA_HD_FORCE_INLINE Vec3F4 operator*(const Vec3F4& a, Float4 s) { return {a.x * s, a.y * s, a.z * s}; }
CA_HD_FORCE_INLINE Vec3F4 operator*(Float4 s, const Vec3F4& a) { return {a.x * s, a.y * s, a.z * s}; }
CA_HD_FORCE_INLINE Float4 dot(const Vec3F4& a, const Vec3F4& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
CA_HD_FORCE_INLINE Vec3F4 cross(const Vec3F4& a, const Vec3F4& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
CA_HD_FORCE_INLINE Float4 lengthSquared(const Vec3F4& a) { return dot(a, a); }
CA_HD_FORCE_INLINE Vec3F4 normalize(const Vec3F4& a) { return a * (1 / Float4::sqrt(dot(a, a))); }  // as Vec3f's
CA_HD_FORCE_INLINE Vec3F4 faceForward(const Vec3F4& v, const Vec3F4& ref) {
    return Vec3F4{Float4::select(dot(v, ref) < 0, -v.x, v.x), Float4::select(dot(v, ref) < 0, -v.y, v.y),
                  Float4::select(dot(v, ref) < 0, -v.z, v.z)};
}
CA_HD_FORCE_INLINE Vec2F4 operator+(const Vec2F4& a, const Vec2F4& b) { return {a.x + b.x, a.y + b.y}; }
CA_HD_FORCE_INLINE Vec2F4 operator-(const Vec2F4& a, const Vec2F4& b) { return {a.x - b.x, a.y - b.y}; }
CA_HD_FORCE_INLINE Vec2F4 operator*(const Vec2F4& a, Float4 s) { return {a.x * s, a.y * s}; }

/// An array index per lane (Index4) and three of them (Vec3u4: a triangle's vertices per lane).
struct Index4 {
    uint32_t k[4];
};
struct Vec3u4 {
    Index4 x, y, z;
};

template <class F>
struct LaneVectors;
template <>
struct LaneVectors<float> {
    using Vec2 = Vec2f;
    using Vec3 = Vec3f;
    using Index = uint32_t;
    using Vec3u = caustica::Vec3u;
};
template <>
struct LaneVectors<Float4> {
    using Vec2 = Vec2F4;
    using Vec3 = Vec3F4;
    using Index = Index4;
    using Vec3u = Vec3u4;
};
template <class F>
using Vec2Of = typename LaneVectors<F>::Vec2;
template <class F>
using Vec3Of = typename LaneVectors<F>::Vec3;
template <class F>
using IndexOf = typename LaneVectors<F>::Index;
template <class F>
using Vec3uOf = typename LaneVectors<F>::Vec3u;

namespace lane {
template <class F>
CA_HD_FORCE_INLINE Vec2Of<F> select(MaskOf<F> m, const Vec2Of<F>& a, const Vec2Of<F>& b) {
    return {select(m, a.x, b.x), select(m, a.y, b.y)};
}
template <class F>
CA_HD_FORCE_INLINE Vec3Of<F> select(MaskOf<F> m, const Vec3Of<F>& a, const Vec3Of<F>& b) {
    return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
/// Lane k of a Vec3F4 as a Vec3f.
CA_HD_FORCE_INLINE Vec3f extract(const Vec3F4& v, int k) { return {v.x[k], v.y[k], v.z[k]}; }

/// Four vectors (or index triples) as the lanes of one.
CA_HD_FORCE_INLINE Vec3F4 fromLanes(const Vec3f& a, const Vec3f& b, const Vec3f& c, const Vec3f& d) {
    return {Float4::fromLanes(a.x, b.x, c.x, d.x), Float4::fromLanes(a.y, b.y, c.y, d.y),
            Float4::fromLanes(a.z, b.z, c.z, d.z)};
}
CA_HD_FORCE_INLINE Vec2F4 fromLanes(const Vec2f& a, const Vec2f& b, const Vec2f& c, const Vec2f& d) {
    return {Float4::fromLanes(a.x, b.x, c.x, d.x), Float4::fromLanes(a.y, b.y, c.y, d.y)};
}
CA_HD_FORCE_INLINE Vec3u4 fromLanes(const Vec3u& a, const Vec3u& b, const Vec3u& c, const Vec3u& d) {
    return {{{a.x, b.x, c.x, d.x}}, {{a.y, b.y, c.y, d.y}}, {{a.z, b.z, c.z, d.z}}};
}

/// Element i of the array `a` (anything with operator[]) in every lane: for one lane the element
/// itself (a reference where operator[] gives one), for Index4 lane k's element i.k[k].
template <class A>
CA_HD_FORCE_INLINE decltype(auto) gather(const A& a, uint32_t i) {
    return a[i];
}
template <class A>
CA_HD_FORCE_INLINE auto gather(const A& a, const Index4& i) {
    return fromLanes(a[i.k[0]], a[i.k[1]], a[i.k[2]], a[i.k[3]]);
}
/// gather where the mask is set; the other lanes read nothing and hold zero. (One lane: the
/// caller has tested the mask.)
template <class A>
CA_HD_FORCE_INLINE decltype(auto) gatherWhere(bool, const A& a, uint32_t i) {
    return a[i];
}
template <class A>
CA_HD_FORCE_INLINE auto gatherWhere(Mask4 m, const A& a, const Index4& i) {
    using T = std::decay_t<decltype(a[0])>;
    const uint32_t bits = m.bits();
    T e[4] = {};
    for (int k = 0; k < 4; ++k)
        if ((bits >> k) & 1u) e[k] = a[i.k[k]];
    return fromLanes(e[0], e[1], e[2], e[3]);
}
}  // namespace lane

/// Axis-aligned bounding box.
struct Bounds3f {
    Vec3f lo{kInfinity, kInfinity, kInfinity};
    Vec3f hi{-kInfinity, -kInfinity, -kInfinity};
    CA_HD void extend(Vec3f p) { lo = min(lo, p); hi = max(hi, p); }
    CA_HD void extend(const Bounds3f& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
    CA_HD bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    CA_HD Vec3f diagonal() const { return hi - lo; }
    CA_HD Vec3f center() const { return (lo + hi) * 0.5f; }
    CA_HD Float surfaceArea() const {
        if (empty()) return 0;
        Vec3f d = diagonal();
        return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
};

/// Tangents s, t that make (s, t, n) an orthonormal basis around the unit normal n (Duff et al.
/// 2017, "Building an Orthonormal Basis, Revisited", listing 3). Generic over the lane type F.
template <class F>
CA_HD_FORCE_INLINE void orthonormalBasis(const Vec3Of<F>& n, Vec3Of<F>& s, Vec3Of<F>& t) {
    const F sign = lane::copysign(lane::splat<F>(1), n.z);
    const F a = -1 / (sign + n.z);
    const F b = n.x * n.y * a;
    s = Vec3Of<F>{1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = Vec3Of<F>{b, sign + n.y * n.y * a, -n.y};
}
/// v in the frame (s, t, n) and back.
template <class F>
CA_HD_FORCE_INLINE Vec3Of<F> frameToLocal(const Vec3Of<F>& s, const Vec3Of<F>& t, const Vec3Of<F>& n,
                                          const Vec3Of<F>& v) {
    return Vec3Of<F>{dot(v, s), dot(v, t), dot(v, n)};
}
template <class F>
CA_HD_FORCE_INLINE Vec3Of<F> frameToWorld(const Vec3Of<F>& s, const Vec3Of<F>& t, const Vec3Of<F>& n,
                                          const Vec3Of<F>& v) {
    return s * v.x + t * v.y + n * v.z;
}

/// Orthonormal basis around a unit normal (orthonormalBasis). Local coordinates have the normal
/// as +z.
struct Frame {
    Vec3f s, t, n;
    Frame() = default;
    CA_HD explicit Frame(Vec3f normal) : n(normal) { orthonormalBasis<float>(n, s, t); }
    CA_HD Vec3f toLocal(Vec3f v) const { return frameToLocal<float>(s, t, n, v); }
    CA_HD Vec3f toWorld(Vec3f v) const { return frameToWorld<float>(s, t, n, v); }
};

}  // namespace caustica
