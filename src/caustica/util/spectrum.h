// spectrum.h — linear RGB radiometric quantities (caustica renders in linear sRGB primaries).
#pragma once

#include "caustica/util/math.h"

namespace caustica {

struct Spectrum {
    Float r = 0, g = 0, b = 0;
    constexpr Spectrum() = default;
    CA_HD constexpr Spectrum(Float r_, Float g_, Float b_) : r(r_), g(g_), b(b_) {}
    CA_HD explicit constexpr Spectrum(Float v) : r(v), g(v), b(v) {}
    CA_HD Float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    CA_HD Float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    CA_HD Spectrum& operator+=(Spectrum o) { r += o.r; g += o.g; b += o.b; return *this; }
    CA_HD Spectrum& operator*=(Spectrum o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
    CA_HD Spectrum& operator*=(Float s) { r *= s; g *= s; b *= s; return *this; }
    CA_HD bool isBlack() const { return r == 0 && g == 0 && b == 0; }
    CA_HD Float maxValue() const { return max(r, max(g, b)); }
    CA_HD Float average() const { return (r + g + b) * (Float(1) / 3); }
    /// Luminance Y of linear sRGB (Rec. 709 primaries).
    CA_HD Float luminance() const { return 0.212671f * r + 0.715160f * g + 0.072169f * b; }
    CA_HD bool isValid() const {  // finite and non-negative
        return std::isfinite(r) && std::isfinite(g) && std::isfinite(b) && r >= 0 && g >= 0 && b >= 0;
    }
};
CA_HD_INLINE Spectrum operator+(Spectrum a, Spectrum b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
CA_HD_INLINE Spectrum operator-(Spectrum a, Spectrum b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
CA_HD_INLINE Spectrum operator*(Spectrum a, Spectrum b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
CA_HD_INLINE Spectrum operator*(Spectrum a, Float s) { return {a.r * s, a.g * s, a.b * s}; }
CA_HD_INLINE Spectrum operator*(Float s, Spectrum a) { return {a.r * s, a.g * s, a.b * s}; }
CA_HD_INLINE Spectrum operator/(Spectrum a, Float s) { Float inv = 1 / s; return a * inv; }
CA_HD_INLINE Spectrum operator/(Spectrum a, Spectrum b) { return {a.r / b.r, a.g / b.g, a.b / b.b}; }
CA_HD_INLINE Spectrum sqrt(Spectrum a) { return {std::sqrt(a.r), std::sqrt(a.g), std::sqrt(a.b)}; }

/// Four spectra, channel by channel: SpectrumOf<Float4> of code generic over the lane type F
/// (util/lane.h; SpectrumOf<float> is Spectrum).
struct SpectrumF4 {
    Float4 r, g, b;
};
CA_HD_FORCE_INLINE SpectrumF4 operator+(const SpectrumF4& a, const SpectrumF4& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
CA_HD_FORCE_INLINE SpectrumF4 operator*(const SpectrumF4& a, const SpectrumF4& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
CA_HD_FORCE_INLINE SpectrumF4 operator*(const SpectrumF4& a, Float4 s) { return {a.r * s, a.g * s, a.b * s}; }
CA_HD_FORCE_INLINE SpectrumF4 operator*(Float4 s, const SpectrumF4& a) { return {a.r * s, a.g * s, a.b * s}; }

template <>
struct LaneForm4<Spectrum> {
    using Type = SpectrumF4;
};
template <class F>
using SpectrumOf = LaneOf<Spectrum, F>;

/// Spectrum::isBlack and Spectrum::maxValue, generic over the lane type F.
template <class F>
CA_HD_FORCE_INLINE MaskOf<F> isBlack(const SpectrumOf<F>& s) {
    return (s.r == 0) & (s.g == 0) & (s.b == 0);
}
template <class F>
CA_HD_FORCE_INLINE F maxValue(const SpectrumOf<F>& s) {
    return lane::max(s.r, lane::max(s.g, s.b));
}

namespace lane {
template <class F>
CA_HD_FORCE_INLINE SpectrumOf<F> select(MaskOf<F> m, const SpectrumOf<F>& a, const SpectrumOf<F>& b) {
    return {select(m, a.r, b.r), select(m, a.g, b.g), select(m, a.b, b.b)};
}
/// Lane k of a SpectrumF4 as a Spectrum.
CA_HD_FORCE_INLINE Spectrum extract(const SpectrumF4& s, int k) { return {s.r[k], s.g[k], s.b[k]}; }
}  // namespace lane

}  // namespace caustica
