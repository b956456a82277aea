// chi2.h — Pearson χ² goodness-of-fit tests of sampling routines against their pdfs, in the
// style of Mitsuba 3's ChiSquareTest and pbrt's chi2 tests (test helper, host only).
//
// A test draws N samples into a histogram over bins of the sampled domain, computes the expected
// count of each bin as N times the pdf integrated numerically over it, pools bins whose expected
// count is below 5, and rejects when the χ² p-value falls below kChi2Significance.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "caustica/util/math.h"

namespace caustica::test {

/// Upper bound of the number of statistical checks (χ², binomial, z-tests) in the suite: with
/// the Bonferroni-corrected per-check significance the family-wise false-alarm rate stays
/// below 1%.
inline constexpr int kChi2TestCount = 200;
inline constexpr double kChi2Significance = 0.01 / kChi2TestCount;

/// Regularised lower incomplete gamma P(a, x) by its power series (Numerical Recipes 6.2.5).
inline double gammaPSeries(double a, double x) {
    double sum = 1 / a, term = sum;
    for (int n = 1; n < 100000; ++n) {
        term *= x / (a + n);
        sum += term;
        if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
    }
    return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

/// Regularised upper incomplete gamma Q(a, x) by its continued fraction (Lentz's method,
/// Numerical Recipes 6.2.7).
inline double gammaQContinuedFraction(double a, double x) {
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

/// Regularised upper incomplete gamma function Q(a, x) = Γ(a, x) / Γ(a).
inline double gammaQ(double a, double x) {
    if (x <= 0) return 1;
    if (x < a + 1) return 1 - gammaPSeries(a, x);
    return gammaQContinuedFraction(a, x);
}

/// Survival function of the χ² distribution with `dof` degrees of freedom: P(X >= chi2).
inline double chi2PValue(double chi2, int dof) { return gammaQ(0.5 * dof, 0.5 * chi2); }

struct Chi2Result {
    double chi2 = 0;
    int dof = 0;
    double pValue = 1;
    int cells = 0;           // cells after pooling
    std::string error;       // non-empty: a sample fell where the pdf is zero
    bool passed() const { return error.empty() && pValue >= kChi2Significance; }
    std::string describe() const {
        char buf[200];
        std::snprintf(buf, sizeof buf, "chi2 = %.2f, dof = %d, p = %.3g (reject below %.3g)%s%s",
                      chi2, dof, pValue, kChi2Significance, error.empty() ? "" : ": ",
                      error.c_str());
        return buf;
    }
};

/// Prints `name: result` when the environment sets CAUSTICA_CHI2_VERBOSE (to tune tests).
inline void printChi2IfVerbose(const std::string& name, const Chi2Result& r) {
    if (std::getenv("CAUSTICA_CHI2_VERBOSE"))
        std::printf("%s: %s\n", name.c_str(), r.describe().c_str());
}

/// Pearson's χ² test of observed against expected counts. Cells with expected count below
/// `minExpected` are pooled into one cell (if that pool is still too small it joins the
/// smallest regular cell). A cell with observations but (numerically) zero expectation fails.
inline Chi2Result chi2Test(const std::vector<double>& observed, const std::vector<double>& expected,
                           double minExpected = 5) {
    Chi2Result r;
    std::vector<size_t> order(observed.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    double poolObs = 0, poolExp = 0;
    std::vector<std::pair<double, double>> cells;  // (observed, expected), ascending expected
    for (size_t i : order) {
        if (expected[i] <= 1e-12 * minExpected && observed[i] > 0) {
            r.error = "cell " + std::to_string(i) + " has " + std::to_string(observed[i]) +
                      " samples but expected count " + std::to_string(expected[i]);
            r.pValue = 0;
            return r;
        }
        if (expected[i] < minExpected) {
            poolObs += observed[i];
            poolExp += expected[i];
        } else {
            cells.emplace_back(observed[i], expected[i]);
        }
    }
    if (poolExp > 0) {
        if (poolExp < minExpected && !cells.empty()) {
            cells.front().first += poolObs;
            cells.front().second += poolExp;
        } else {
            cells.emplace_back(poolObs, poolExp);
        }
    }
    for (const auto& [o, e] : cells) r.chi2 += (o - e) * (o - e) / e;
    r.cells = int(cells.size());
    r.dof = r.cells - 1;
    r.pValue = r.dof > 0 ? chi2PValue(r.chi2, r.dof) : 1;
    return r;
}

/// χ² test that `draw(0) ... draw(draws - 1)` are uniform on [0, 1), over `bins` equal bins. A value
/// outside [0, 1) fails the test by name.
inline Chi2Result chi2UniformOnUnitInterval(int bins, int draws, const std::function<double(int)>& draw) {
    std::vector<double> observed(size_t(bins), 0.0), expected(size_t(bins), double(draws) / bins);
    for (int i = 0; i < draws; ++i) {
        const double u = draw(i);
        if (!(u >= 0 && u < 1)) {
            Chi2Result r;
            r.pValue = 0;
            r.error = "draw " + std::to_string(i) + " = " + std::to_string(u) + " is outside [0, 1)";
            return r;
        }
        observed[std::min(size_t(bins) - 1, size_t(u * bins))] += 1;
    }
    return chi2Test(observed, expected);
}

/// Two-sided p-value of k successes in n Bernoulli(p) trials (normal approximation, valid for
/// n p (1 - p) >> 1).
inline double binomialPValue(double k, double n, double p) {
    const double var = n * p * (1 - p);
    if (var <= 0) return k == n * p ? 1.0 : 0.0;
    return std::erfc(std::fabs(k - n * p) / std::sqrt(2 * var));
}

/// z such that P(Z > z) = p for a standard normal Z (bisection on the complementary error
/// function): the one-sided critical value of a z-test at significance p.
inline double normalUpperQuantile(double p) {
    double lo = 0, hi = 40;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Composite Simpson weights for `k` (even) subintervals: 1 4 2 4 ... 4 1 (times h/3).
inline double simpsonWeight(int i, int k) { return (i == 0 || i == k) ? 1 : (i % 2 ? 4 : 2); }

/// A grid of bins over a cap of the sphere of directions in spherical coordinates (θ, φ)
/// relative to a frame: θ ∈ [0, thetaMax] in `nTheta` equal steps (with thetaMax = π and an even
/// count, an edge lies on the horizon θ = π/2 where one-sided pdfs are discontinuous),
/// φ ∈ [0, 2π) in `nPhi` steps. One more bin collects "no sample" and directions beyond thetaMax.
struct SphereGrid {
    Frame frame;
    int nTheta = 64, nPhi = 128;
    double thetaMax = M_PI;

    int bins() const { return nTheta * nPhi + 1; }
    /// Bin of a unit world direction.
    int bin(Vec3f w) const {
        const Vec3f l = frame.toLocal(w);
        const double theta = std::atan2(std::hypot(double(l.x), double(l.y)), double(l.z));
        double phi = std::atan2(double(l.y), double(l.x));
        if (phi < 0) phi += 2 * M_PI;
        if (theta > thetaMax) return bins() - 1;
        const int i = std::min(int(theta / thetaMax * nTheta), nTheta - 1);
        const int j = std::min(int(phi / (2 * M_PI) * nPhi), nPhi - 1);
        return i * nPhi + j;
    }
    Vec3f direction(double theta, double phi) const {
        const double s = std::sin(theta);
        return frame.toWorld(Vec3f(Float(s * std::cos(phi)), Float(s * std::sin(phi)),
                                   Float(std::cos(theta))));
    }
    /// N times ∫ pdf over each bin, by composite Simpson on `k` (even) subintervals per bin and
    /// axis; the last bin gets the remainder (see below). The θ nodes on a bin's edges are moved inside the
    /// bin by 1e-5 rad (at most 1% of its width; float directions are exact to ~1e-7), so that a
    /// pdf that jumps on a bin edge (the horizon of a one-sided BSDF, the rim of a cone) is
    /// integrated with the limit from inside each bin.
    std::vector<double> expected(const std::function<double(Vec3f)>& pdf, double n,
                                 int k = 4) const {
        const int np = nPhi * k + 1;
        const double dt = thetaMax / (nTheta * k), dp = 2 * M_PI / (nPhi * k);
        std::vector<double> e(bins(), 0.0);
        std::vector<double> f(size_t(k + 1) * np);
        const double edgeShift = std::min(1e-5, 0.01 * dt * k);
        double total = 0;
        for (int i = 0; i < nTheta; ++i) {
            for (int a = 0; a <= k; ++a) {
                const double shift = a == 0 ? edgeShift : (a == k ? -edgeShift : 0.0);
                const double theta = (i * k + a) * dt + shift;
                for (int b = 0; b < np; ++b)
                    f[size_t(a) * np + b] = pdf(direction(theta, b * dp)) * std::sin(theta);
            }
            for (int j = 0; j < nPhi; ++j) {
                double s = 0;
                for (int a = 0; a <= k; ++a)
                    for (int b = 0; b <= k; ++b)
                        s += simpsonWeight(a, k) * simpsonWeight(b, k) *
                             f[size_t(a) * np + (j * k + b)];
                const double v = std::max(0.0, s * dt * dp / 9 * n);
                e[i * nPhi + j] = v;
                total += v;
            }
        }
        // Uniform numbers come from a 24-bit lattice, so an event of measure zero in the
        // continuum (a warp landing exactly on the domain's boundary, where a sampler may refuse
        // it) has a probability of a few 2^-24: the last bin expects at least N 2^-20.
        e.back() = std::max(n * 0x1p-20, n - total);
        return e;
    }
};

/// Runs a χ² test of a direction sampler against its pdf on `grid`. `sample(i, w)` draws sample
/// i, returning false for "no sample". The expected counts are integrated with k and 2k Simpson
/// subintervals per bin, doubling k (from `k`, up to 32) until the two differ by less than a
/// tenth of the χ² statistic's standard deviation sqrt(2 dof) (the amount by which quadrature
/// error could inflate E[χ²]); the 2k result is used.
inline Chi2Result chi2Directions(const SphereGrid& grid, int n,
                                 const std::function<bool(int, Vec3f&)>& sample,
                                 const std::function<double(Vec3f)>& pdf, int k = 4) {
    std::vector<double> obs(grid.bins(), 0.0);
    for (int i = 0; i < n; ++i) {
        Vec3f w;
        if (sample(i, w))
            obs[grid.bin(w)] += 1;
        else
            obs.back() += 1;
    }
    std::vector<double> coarse = grid.expected(pdf, n, k);
    for (;; k *= 2) {
        std::vector<double> fine = grid.expected(pdf, n, 2 * k);
        Chi2Result r = chi2Test(obs, fine);
        double quad = 0;
        for (size_t i = 0; i < fine.size(); ++i)
            if (fine[i] >= 5) quad += (coarse[i] - fine[i]) * (coarse[i] - fine[i]) / fine[i];
        if (!r.error.empty() || quad <= 0.1 * std::sqrt(2.0 * std::max(r.dof, 1))) return r;
        if (2 * k >= 32) {
            r.error = "pdf quadrature not converged (chi2 distance " + std::to_string(quad) +
                      " between " + std::to_string(k) + " and " + std::to_string(2 * k) +
                      " subintervals): raise the grid resolution";
            return r;
        }
        coarse = std::move(fine);
    }
}

}  // namespace caustica::test
