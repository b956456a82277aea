// filter.h — image reconstruction filters, exactly as Mitsuba 3's rfilter plugins define them
// (src/rfilters/{box,tent,gaussian}.cpp). Filters are not normalised: the film divides the
// weighted radiance sum by the weight sum, as Mitsuba's ImageBlock does.
//
// Offsets are in pixels, measured from a pixel centre (pixel i has its centre at i + 0.5).
#pragma once

#include <cmath>
#include <string>

#include "caustica/scene/scene.h"
#include "caustica/util/error.h"
#include "caustica/util/math.h"

namespace caustica {

/// A separable 2-D reconstruction filter, w(dx, dy) = w(dx) * w(dy).
///   box:      radius 0.5,        w(x) = 1 for -0.5 <= x < 0.5, else 0 (half-open, as Mitsuba)
///   tent:     radius r (def. 1), w(x) = max(0, 1 - |x| / r)
///   gaussian: stddev s (def. 0.5), radius r = 4 s,
///             w(x) = max(0, exp(-x^2 / (2 s^2)) - exp(-r^2 / (2 s^2)))
struct Filter {
    FilterType type = FilterType::Gaussian;
    Float radius = 2.0f;     // support half-width in pixels: w(x) = 0 for |x| >= radius
    Float stddev = 0.5f;     // gaussian only
    Float invRadius = 0.5f;  // tent only
    Float alpha = -2.0f;     // gaussian only: -1 / (2 stddev^2)
    Float bias = 0.0f;       // gaussian only: exp(alpha * radius^2), subtracted so w(radius) = 0

    static Filter box() {
        Filter f;
        f.type = FilterType::Box;
        f.radius = 0.5f;
        f.invRadius = 2.0f;
        return f;
    }
    static Filter tent(Float radius = 1.0f) {
        if (!(radius > 0) || !std::isfinite(radius))
            throw Error("tent filter radius must be positive and finite, got " +
                        std::to_string(radius));
        Filter f;
        f.type = FilterType::Tent;
        f.radius = radius;
        f.invRadius = 1.0f / radius;
        return f;
    }
    static Filter gaussian(Float stddev = 0.5f) {
        if (!(stddev > 0) || !std::isfinite(stddev))
            throw Error("gaussian filter stddev must be positive and finite, got " +
                        std::to_string(stddev));
        Filter f;
        f.type = FilterType::Gaussian;
        f.stddev = stddev;
        f.radius = 4.0f * stddev;  // Mitsuba cuts off after 4 standard deviations
        f.invRadius = 1.0f / f.radius;
        f.alpha = -1.0f / (2.0f * stddev * stddev);
        f.bias = std::exp(f.alpha * f.radius * f.radius);
        return f;
    }
    /// Builds the filter a scene asks for. The box ignores desc.radius (always 0.5) and the
    /// gaussian derives its radius from desc.stddev (4 stddev); the tent uses desc.radius.
    static Filter fromDesc(const FilterDesc& desc) {
        switch (desc.type) {
            case FilterType::Box:
                return box();
            case FilterType::Tent:
                return tent(desc.radius);
            case FilterType::Gaussian:
                return gaussian(desc.stddev);
        }
        throw Error("unknown filter type " + std::to_string(uint32_t(desc.type)));
    }

    /// 1-D weight at offset x (pixels) from a pixel centre.
    CA_HD Float eval(Float x) const {
        switch (type) {
            case FilterType::Box:
                return (x >= -0.5f && x < 0.5f) ? Float(1) : Float(0);
            case FilterType::Tent:
                return max(Float(0), 1.0f - std::fabs(x * invRadius));
            case FilterType::Gaussian:
                return max(Float(0), std::exp(alpha * x * x) - bias);
        }
        return 0;
    }
    /// 2-D weight w(dx) * w(dy).
    CA_HD Float eval(Float dx, Float dy) const { return eval(dx) * eval(dy); }
    CA_HD Float eval(Vec2f d) const { return eval(d.x) * eval(d.y); }

    /// Source pixels on each side of an output pixel whose samples can have non-zero weight: a
    /// sample of source pixel x + d sits at offset d + u - 0.5 with u in [0, 1), so |d| < radius + 0.5.
    int footprint() const { return int(std::ceil(double(radius) + 0.5)) - 1; }

    /// Analytic integral of the 1-D weight over the real line (the 2-D integral is its square).
    double integral() const {
        switch (type) {
            case FilterType::Box:
                return 1.0;
            case FilterType::Tent:
                return double(radius);
            case FilterType::Gaussian: {
                // int_{-r}^{r} exp(-x^2 / (2 s^2)) dx - 2 r bias
                const double pi = 3.14159265358979323846, s = stddev, r = radius;
                return s * std::sqrt(2.0 * pi) * std::erf(r / (s * std::sqrt(2.0))) -
                       2.0 * r * bias;
            }
        }
        return 0;
    }
};

}  // namespace caustica
