// denoise_nlm.h — the per-pixel kernels of caustica's feature-guided non-local-means denoiser
// (shared kernel code: CA_HD, no heap, no exceptions). The host entry is film/denoise_nlm_pass.h.
//
// The filter is the joint NL-means of Rousselle, Manzi and Zwicker, "Robust denoising using
// feature and color information", Pacific Graphics 2013 (RMZ13), with one candidate filter:
//
//   out(p) = sum_q w(p,q) u(q) / sum_q w(p,q),     q in the (2r+1)^2 window around p,
//   w(p,q) = min(w_c(p,q), w_f(p,q)).
//
// Colour weight (RMZ13 eq. 2-3, from Rousselle et al. 2012, eq. 7): a patch distance over the
// (2f+1)^2 patch offsets n and the 3 channels i, with variance cancellation,
//
//   d2_i(p,q) = [ (u_i(p) - u_i(q))^2 - alpha (V_i(p) + min(V_i(p), V_i(q))) ]
//               / [ eps + k_c^2 (V_i(p) + V_i(q)) ],
//   d2_c(P,Q) = mean over n and i of d2_i(p+n, q+n),     w_c = exp(-max(0, d2_c)),
//
// where V is the per-pixel variance of the mean (given, or estimated: estimateVariance below).
// Feature weight (RMZ13 eq. 5), per feature j (albedo, normal, depth), with its gradient at p:
//
//   Phi2_j(p,q) = |f_j(p) - f_j(q)|^2 / ( k_f^2 max(tau, |grad f_j(p)|^2) ),
//   w_f = exp(-max_j Phi2_j).
//
// RMZ13's feature-variance terms are left out (caustica's feature images carry no variance);
// the gradient term already relaxes the weight where a feature varies across the pixel.
// Non-finite colour values (NaN, Inf) make a pixel "invalid": it never contributes as q, its
// patch terms are skipped, and an invalid p is filtered from its valid neighbours with the
// feature weight alone (0 when it has none). Every pixel's loop order is fixed, so the result
// does not depend on the number of threads.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "caustica/util/platform.h"

namespace caustica {

/// Parameters of the NL-means filter (RMZ13's values as defaults, except k_c: docs/DENOISING.md).
struct NlmParams {
    int radius = 8;          ///< r: the search window is (2r+1)^2 pixels
    int patchRadius = 1;     ///< f: patches of (2f+1)^2 pixels
    float kColor = 0.8f;     ///< k_c: colour sensitivity (smaller: sharper); RMZ13 0.45
    float kFeature = 0.6f;   ///< k_f: feature sensitivity
    float alpha = 1.0f;      ///< variance cancellation strength
    float tau = 1e-3f;       ///< floor of the feature gradient term
};

/// Up to this many guide features (albedo, normal, depth).
inline constexpr int kMaxNlmFeatures = 3;

/// One guide feature: `channels` floats per pixel (1 for depth, 3 for albedo/normal), finite.
struct NlmFeature {
    const float* values = nullptr;
    int channels = 0;
};

/// What the kernels read and write (device pointers, row-major, top row first).
struct NlmView {
    int width = 0, height = 0;
    const float* color = nullptr;     ///< 3 per pixel; non-finite values zeroed by prepare
    const uint8_t* valid = nullptr;   ///< 1 where the input colour was finite
    const float* variance = nullptr;  ///< 3 per pixel, variance of the mean, >= 0
    NlmFeature features[kMaxNlmFeatures];
    int featureCount = 0;
    NlmParams params;
};

CA_HD_INLINE bool nlmFinite(float v) { return v - v == 0.0f; }  // false for NaN and +-Inf

/// Copies pixel i's colour into `color` (0 where not finite) and sets valid[i].
CA_HD_INLINE void nlmPrepareColor(const float* input, float* color, uint8_t* valid, size_t i) {
    const float r = input[3 * i], g = input[3 * i + 1], b = input[3 * i + 2];
    const bool ok = nlmFinite(r) && nlmFinite(g) && nlmFinite(b);
    valid[i] = ok ? 1 : 0;
    color[3 * i] = ok ? r : 0.0f;
    color[3 * i + 1] = ok ? g : 0.0f;
    color[3 * i + 2] = ok ? b : 0.0f;
}

CA_HD_INLINE int nlmClamp(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

/// Mean of term(c, t) (t: 3 floats the term fills) over the valid pixels c within `radius` of
/// (px, py) (outside the image: left out), written to mean[0..2]; 0 when there are none.
template <class Term>
CA_HD_INLINE void nlmValidMean(const NlmView& v, int px, int py, int radius, const Term& term, float mean[3]) {
    float sum[3] = {0, 0, 0};
    int count = 0;
    for (int y = py - radius; y <= py + radius; ++y)
        for (int x = px - radius; x <= px + radius; ++x) {
            if (x < 0 || y < 0 || x >= v.width || y >= v.height) continue;
            const size_t c = size_t(y) * size_t(v.width) + size_t(x);
            if (!v.valid[c]) continue;
            float t[3];
            term(c, t);
            for (int ch = 0; ch < 3; ++ch) sum[ch] += t[ch];
            ++count;
        }
    for (int ch = 0; ch < 3; ++ch) mean[ch] = count > 0 ? sum[ch] / float(count) : 0.0f;
}

/// Per-pixel variance of the mean when none is given: 9/8 times the mean squared residual of the
/// colour against its 3x3 box mean, averaged over the 5x5 neighbourhood (for white noise of
/// variance s^2 the residual has variance 8/9 s^2). Overestimates at edges, where the feature
/// weight takes over.
CA_HD_INLINE void nlmEstimateVariance(const NlmView& v, float* variance, size_t i) {
    const int px = int(i % size_t(v.width)), py = int(i / size_t(v.width));
    const float* color = v.color;
    auto squaredResidual = [&v, color](size_t c, float t[3]) {
        const int x = int(c % size_t(v.width)), y = int(c / size_t(v.width));
        float box[3];
        nlmValidMean(v, x, y, 1, [color](size_t k, float u[3]) {
            for (int ch = 0; ch < 3; ++ch) u[ch] = color[3 * k + ch];
        }, box);
        for (int ch = 0; ch < 3; ++ch) {
            const float r = color[3 * c + ch] - box[ch];
            t[ch] = r * r * (9.0f / 8.0f);
        }
    };
    nlmValidMean(v, px, py, 2, squaredResidual, variance + 3 * i);
}

/// A given variance smoothed over the 5x5 neighbourhood (valid pixels): a variance from a few
/// batches is itself noisy (3 degrees of freedom from 4 batches), and a pixel whose batches
/// happen to agree would otherwise claim a variance of 0 and refuse every neighbour.
CA_HD_INLINE void nlmSmoothVariance(const NlmView& v, const float* given, float* variance, size_t i) {
    const int px = int(i % size_t(v.width)), py = int(i / size_t(v.width));
    nlmValidMean(v, px, py, 2, [given](size_t c, float t[3]) {
        for (int ch = 0; ch < 3; ++ch) {
            const float g = given[3 * c + ch];
            t[ch] = nlmFinite(g) && g > 0.0f ? g : 0.0f;
        }
    }, variance + 3 * i);
}

/// Squared gradient magnitude of feature `f` at (x, y), central differences (one-sided at the
/// border), summed over its channels.
CA_HD_INLINE float nlmFeatureGradient2(const NlmView& v, const NlmFeature& f, int x, int y) {
    const int x0 = nlmClamp(x - 1, 0, v.width - 1), x1 = nlmClamp(x + 1, 0, v.width - 1);
    const int y0 = nlmClamp(y - 1, 0, v.height - 1), y1 = nlmClamp(y + 1, 0, v.height - 1);
    const float sx = x1 > x0 ? 1.0f / float(x1 - x0) : 0.0f, sy = y1 > y0 ? 1.0f / float(y1 - y0) : 0.0f;
    const size_t w = size_t(v.width);
    float g2 = 0.0f;
    for (int ch = 0; ch < f.channels; ++ch) {
        const float gx = (f.values[(size_t(y) * w + size_t(x1)) * f.channels + ch] -
                          f.values[(size_t(y) * w + size_t(x0)) * f.channels + ch]) * sx;
        const float gy = (f.values[(size_t(y1) * w + size_t(x)) * f.channels + ch] -
                          f.values[(size_t(y0) * w + size_t(x)) * f.channels + ch]) * sy;
        g2 += gx * gx + gy * gy;
    }
    return g2;
}

/// RMZ13 colour patch distance d2_c(P, Q) between the patches around pixels a and b (eq. 2-3);
/// pixels outside the image or invalid on either side are skipped. Returns 0 when none is left.
CA_HD_INLINE float nlmColorDistance(const NlmView& v, int ax, int ay, int bx, int by) {
    const NlmParams& pr = v.params;
    const float k2 = pr.kColor * pr.kColor;
    const size_t w = size_t(v.width);
    float sum = 0.0f;
    int terms = 0;
    for (int ny = -pr.patchRadius; ny <= pr.patchRadius; ++ny)
        for (int nx = -pr.patchRadius; nx <= pr.patchRadius; ++nx) {
            const int pxn = ax + nx, pyn = ay + ny, qxn = bx + nx, qyn = by + ny;
            if (pxn < 0 || pyn < 0 || pxn >= v.width || pyn >= v.height) continue;
            if (qxn < 0 || qyn < 0 || qxn >= v.width || qyn >= v.height) continue;
            const size_t p = size_t(pyn) * w + size_t(pxn), q = size_t(qyn) * w + size_t(qxn);
            if (!v.valid[p] || !v.valid[q]) continue;
            for (int ch = 0; ch < 3; ++ch) {
                const float vp = v.variance[3 * p + ch], vq = v.variance[3 * q + ch];
                const float d = v.color[3 * p + ch] - v.color[3 * q + ch];
                const float vmin = vp < vq ? vp : vq;
                sum += (d * d - pr.alpha * (vp + vmin)) / (1e-10f + k2 * (vp + vq));
            }
            terms += 3;
        }
    return terms > 0 ? sum / float(terms) : 0.0f;
}

/// The filtered colour of pixel i (writes 3 floats to out[3i..]).
CA_HD_INLINE void nlmFilterPixel(const NlmView& v, float* out, size_t i) {
    const NlmParams& pr = v.params;
    const int px = int(i % size_t(v.width)), py = int(i / size_t(v.width));
    const size_t w = size_t(v.width);
    const bool centreValid = v.valid[i] != 0;

    // Step 1: the feature gradient term at p (RMZ13 eq. 5's denominator).
    float featureNorm[kMaxNlmFeatures];
    for (int j = 0; j < v.featureCount; ++j) {
        const float g2 = nlmFeatureGradient2(v, v.features[j], px, py);
        featureNorm[j] = 1.0f / (pr.kFeature * pr.kFeature * (g2 > pr.tau ? g2 : pr.tau));
    }

    // Step 2: the weighted mean over the search window, in a fixed order, accumulated as
    // differences from u(p) so that a constant image comes back bit-exact.
    const float centre[3] = {v.color[3 * i], v.color[3 * i + 1], v.color[3 * i + 2]};
    float acc[3] = {0, 0, 0};
    float weightSum = 0.0f;
    for (int dy = -pr.radius; dy <= pr.radius; ++dy)
        for (int dx = -pr.radius; dx <= pr.radius; ++dx) {
            const int qx = px + dx, qy = py + dy;
            if (qx < 0 || qy < 0 || qx >= v.width || qy >= v.height) continue;
            const size_t q = size_t(qy) * w + size_t(qx);
            if (!v.valid[q]) continue;
            float phi2 = 0.0f;
            for (int j = 0; j < v.featureCount; ++j) {
                const NlmFeature& f = v.features[j];
                float d2 = 0.0f;
                for (int ch = 0; ch < f.channels; ++ch) {
                    const float d = f.values[i * f.channels + ch] - f.values[q * f.channels + ch];
                    d2 += d * d;
                }
                const float phi = d2 * featureNorm[j];
                phi2 = phi > phi2 ? phi : phi2;
            }
            float weight = std::exp(-phi2);
            if (centreValid) {
                const float dc = nlmColorDistance(v, px, py, qx, qy);
                const float wc = std::exp(-(dc > 0.0f ? dc : 0.0f));
                weight = wc < weight ? wc : weight;
            }
            for (int ch = 0; ch < 3; ++ch) acc[ch] += weight * (v.color[3 * q + ch] - centre[ch]);
            weightSum += weight;
        }
    for (int ch = 0; ch < 3; ++ch) out[3 * i + ch] = weightSum > 0.0f ? centre[ch] + acc[ch] / weightSum : 0.0f;
}

}  // namespace caustica
