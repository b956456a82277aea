// mlt_kernel.h — the per-chain kernels of primary-sample-space Metropolis light transport
// (Kelemen et al. 2002) with split-transition multiple proposals (Frolov & Galaktionov 2017,
// Algorithm 1), shared by CPU and GPU.
//
// The target function is I(u) = luminance(F(u)), F(u) the path tracer's radiance estimate for
// the primary sample vector u (film position from u0, u1, lens from u2, u3; the path from the rest). Each
// iteration every chain, in lock step:
//   traceProposals (per chain and proposal; side by side in groups) builds proposal y_j from the current
//                  state x on the fly (small step, or large step with probability pLarge) and
//                  runs the unchanged path tracer on it;
//   advanceChain   (one work item per chain) computes a_j = min(1, I(y_j) / I(x)), splats y_j with
//                  weight a_j and x with k - sum(a_j), draws the next state in proportion to
//                  (k - sum a_j, a_1 ... a_k), and on a move rewrites the stored state from the
//                  accepted proposal's stream.
// Splats combine the chains with the large steps by the balance heuristic (Kelemen et al. 2002,
// sec. 5): a large-step proposal is also an ordinary Monte Carlo sample (density 1 in primary
// sample space, k pLarge of them per chain and iteration on average), the chain's expected-value
// splats have density I / b (k per chain and iteration), so a point x splatted with chain weight w
// contributes (w + [x is a large-step proposal]) F(x) / (I(x) / b + pLarge); the driver divides
// by k x chains x iterations. With pLarge = 0 this is plain MLT (w b F / I); where I is small the
// large steps' path-tracing estimate takes over, which keeps dark pixels from starving.
// The b in those weights is fixed for the whole render (the bootstrap's estimate b0): any b0 > 0
// gives valid balance weights, but the chain part then estimates (b0 / b) times its share of the
// image, b the true normalisation. So the two parts go to separate layers and the driver scales
// the chain layer by b / b0 at the end, b estimated from every sample so far — the early
// estimate's error does not stay in the image.
#pragma once

#include <cstdint>

#include "caustica/integrators/mlt/mlt_splat.h"
#include "caustica/integrators/mlt/mlt_state.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/integrators/path/path_lanes.h"
#include "caustica/scene/camera.h"

namespace caustica {

/// Parameters of the Metropolis step that kernels read.
struct MltStepParams {
    uint64_t seed = 0;
    uint32_t iteration = 0;
    // Global index of this driver's chain 0 (chains split over ranks): the proposal streams are
    // keyed by the global chain index, so the union of the ranks' chains is one process's.
    uint32_t chainOffset = 0;
    uint32_t proposals = 1;            // k
    Float largeStepProbability = 0.1f;
    float b = 1;                       // b0: the bootstrap's estimate of E[I], for the splat weights
    // Target I = luminance(F) x pixelWeight[pixel] when set (relative target: the inverse of a
    // smoothed estimate of the pixel's brightness, so every pixel draws about equal effort);
    // plain luminance when null.
    const float* pixelWeight = nullptr;
    MltMutation mutation;
    PathSettings path;
    int width = 0, height = 0;
};

/// Per-chain arrays (device pointers) besides the stored primary samples.
template <class Store>
struct MltChainView {
    Store store;
    uint32_t chains = 0;
    Vec2f* pos = nullptr;         // current state: film position
    Spectrum* value = nullptr;    //                F(x)
    float* importance = nullptr;  //                I(x)
    uint16_t* usedDims = nullptr; //                stored coordinates its path used: min(U, dims)
    // Proposals of this iteration, index chain * k + j.
    Vec2f* proposalPos = nullptr;
    Spectrum* proposalValue = nullptr;
    float* proposalImportance = nullptr;
    uint32_t* proposalRays = nullptr;
    uint16_t* proposalDims = nullptr;
    MltSplat* splats = nullptr;       // chain * (k + 1) + (0: current state, 1 + j: proposal j)
    float* largeStepSum = nullptr;    // per chain: sum of I over this iteration's large steps
    uint32_t* largeSteps = nullptr;   // per chain: their number
    uint32_t* accepted = nullptr;     // per chain: 1 if the chain moved this iteration
};

/// Stream key of proposal j of `chain` at `iteration`.
CA_HD_INLINE uint64_t mltProposalKey(uint64_t seed, uint32_t chain, uint32_t iteration, uint32_t j) {
    return hashCombine(hashCombine(hashCombine(mix64(seed + 0x2545f4914f6cdd1dull), chain), iteration), j);
}
/// Stream key of bootstrap sample i (independent of every chain stream).
CA_HD_INLINE uint64_t mltBootstrapKey(uint64_t seed, uint64_t i) {
    return hashCombine(mix64(seed ^ 0x8cb92ba72f3d8dd7ull), i);
}
CA_HD_INLINE bool mltIsLargeStep(uint64_t key, Float largeStepProbability) {
    return uniformFloat(mix64(key ^ 0xd1b54a32d192ed03ull)) < largeStepProbability;
}

/// Pixel index of a film position (clamped to the image).
CA_HD_INLINE uint32_t mltPixelOf(Vec2f pos, int width, int height) {
    const int x = min(max(int(pos.x), 0), width - 1), y = min(max(int(pos.y), 0), height - 1);
    return uint32_t(y) * uint32_t(width) + uint32_t(x);
}
/// The target function I of a path with value F through film position pos.
CA_HD_INLINE float mltImportance(const Spectrum& F, Vec2f pos, const MltStepParams& p) {
    const float lum = float(F.luminance());
    return p.pixelWeight ? lum * p.pixelWeight[mltPixelOf(pos, p.width, p.height)] : lum;
}

/// The camera ray of a primary sample: the film position from its first two numbers, the lens
/// position from the next two (drawn always, a fixed layout; used by a thin lens only).
template <class Sampler>
CA_HD_INLINE Ray primaryCameraRay(const SceneView& scene, Sampler& sampler, int width, int height, Vec2f& pos) {
    const Vec2f u = sampler.get2D();
    pos = Vec2f(u.x * Float(width), u.y * Float(height));
    const Vec2f lens = sampler.get2D();
    return generateCameraRay(scene.camera, pos, lens);
}

/// A path's radiance as the target sees it: invalid radiance (NaN, Inf, negative) counts as zero.
CA_HD_INLINE Spectrum mltValidRadiance(const Spectrum& L) { return L.isValid() ? L : Spectrum(0); }

/// Runs the path tracer on the primary samples `sampler` produces: the film position from the
/// first two (pos), the lens position from the next two, the path from the rest.
template <class Intersector, class Sampler>
CA_HD Spectrum evaluatePrimarySample(const SceneView& scene, const Intersector& accel, Sampler& sampler,
                                     const PathSettings& settings, int width, int height, Vec2f& pos,
                                     uint32_t& rays) {
    const Ray cameraRay = primaryCameraRay(scene, sampler, width, height, pos);
    return mltValidRadiance(pathRadiance(scene, accel, sampler, cameraRay, settings, rays));
}

/// Work items of the proposal and bootstrap kernels per launch item: a group traced side by side
/// where the intersector answers packets (path_lanes.h), else one.
template <class Intersector>
constexpr uint32_t mltItemsPerLaunch() {
    return laneCount<Intersector>() > 1 ? 64u : 1u;
}

/// Builds and traces proposals [first, first + n) (item = chain * k + j; n <=
/// mltItemsPerLaunch<I>()), each from its chain's current state with its own stream, the paths
/// side by side (tracePathsSideBySide: each as evaluatePrimarySample would trace it).
template <class Store, class Intersector>
CA_HD void traceProposals(const SceneView& scene, const Intersector& accel, const MltChainView<Store>& v,
                          const MltStepParams& p, uint32_t first, uint32_t n) {
    Vec2f pos[mltItemsPerLaunch<Intersector>()];
    tracePathsSideBySide<Intersector, MltProposalSampler<Store>>(
        scene, accel, p.path, n,
        [&](size_t l, MltProposalSampler<Store>& sampler) {
            const uint32_t item = first + uint32_t(l), chain = item / p.proposals, j = item % p.proposals;
            const uint64_t key = mltProposalKey(p.seed, p.chainOffset + chain, p.iteration, j);
            sampler = MltProposalSampler<Store>(&v.store, chain, v.usedDims[chain], key,
                                                mltIsLargeStep(key, p.largeStepProbability), p.mutation);
            return primaryCameraRay(scene, sampler, p.width, p.height, pos[l]);
        },
        [&](size_t l, const MltProposalSampler<Store>& sampler, const Spectrum& L, uint32_t rays) {
            const uint32_t item = first + uint32_t(l);
            const Spectrum F = mltValidRadiance(L);
            v.proposalDims[item] = uint16_t(min(sampler.dimension(), v.store.dims));
            v.proposalPos[item] = pos[l];
            v.proposalValue[item] = F;
            v.proposalImportance[item] = mltImportance(F, pos[l], p);
            v.proposalRays[item] = rays;
        });
}

/// What a point with value F, importance I and combined weight w splats (see the header).
CA_HD_INLINE Spectrum mltSplatValue(const Spectrum& F, float I, float w, const MltStepParams& p) {
    const float density = I / p.b + float(p.largeStepProbability);
    return density > 0 && w > 0 ? F * (w / density) : Spectrum(0);
}

/// advanceChain for one chain: splats, selection of the next state, state update.
template <class Store>
CA_HD void advanceChain(const MltChainView<Store>& v, const MltStepParams& p, uint32_t chain) {
    const uint32_t k = p.proposals;
    const float Ix = v.importance[chain];
    float sumA = 0, largeSum = 0;
    uint32_t largeCount = 0;
    MltSplat* splats = v.splats + size_t(chain) * (k + 1);
    for (uint32_t j = 0; j < k; ++j) {
        const uint32_t item = chain * k + j;
        const float Iy = v.proposalImportance[item];
        const uint64_t key = mltProposalKey(p.seed, p.chainOffset + chain, p.iteration, j);
        const bool large = mltIsLargeStep(key, p.largeStepProbability);
        if (large) {
            largeSum += Iy;
            ++largeCount;
        }
        // A chain started where I = 0 (uniform start only) accepts any proposal.
        const float a = Ix > 0 ? min(1.0f, Iy / Ix) : 1.0f;
        sumA += a;
        const Spectrum Fy = v.proposalValue[item];
        splats[1 + j] = MltSplat{v.proposalPos[item], mltSplatValue(Fy, Iy, a, p),
                                 large ? mltSplatValue(Fy, Iy, 1.0f, p) : Spectrum(0)};
    }
    const float stay = max(0.0f, float(k) - sumA);
    splats[0] = MltSplat{v.pos[chain], mltSplatValue(v.value[chain], Ix, stay, p), Spectrum(0)};
    v.largeStepSum[chain] = largeSum;
    v.largeSteps[chain] = largeCount;

    // Next state in proportion to (k - sum a_j, a_1, ..., a_k).
    const uint64_t selectKey = mltProposalKey(p.seed, p.chainOffset + chain, p.iteration, 0xffffffffu);
    float u = uniformFloat(mix64(selectKey)) * float(k);
    int chosen = -1;
    if (u >= stay) {
        u -= stay;
        for (uint32_t j = 0; j < k; ++j) {
            const float a = Ix > 0 ? min(1.0f, v.proposalImportance[chain * k + j] / Ix) : 1.0f;
            if (a > 0) {
                chosen = int(j);  // the last proposal with a > 0 absorbs rounding at the end
                if (u < a) break;
            }
            u -= a;
        }
    }
    v.accepted[chain] = chosen >= 0 ? 1u : 0u;
    if (chosen < 0) return;
    const uint32_t item = chain * k + uint32_t(chosen);
    const uint64_t key = mltProposalKey(p.seed, p.chainOffset + chain, p.iteration, uint32_t(chosen));
    MltProposalSampler<Store> sampler(&v.store, chain, v.usedDims[chain], key,
                                      mltIsLargeStep(key, p.largeStepProbability), p.mutation);
    // The coordinates the accepted path used; raw(d) reads the old value of d only, so updating
    // in place is safe.
    const uint32_t used = v.proposalDims[item];
    for (uint32_t d = 0; d < used; ++d) v.store.set(chain, d, sampler.raw(d));
    v.usedDims[chain] = uint16_t(used);
    v.pos[chain] = v.proposalPos[item];
    v.value[chain] = v.proposalValue[item];
    v.importance[chain] = v.proposalImportance[item];
}

/// Bootstrap samples first .. first + n - 1 (n <= mltItemsPerLaunch<I>(); ordinary Monte Carlo
/// paths from fresh primary samples, side by side): importance[l] under p's target, pixel[l] the
/// pixel it falls in and rays[l] its rays, for sample first + l.
template <class Store, class Intersector>
CA_HD void bootstrapImportances(const SceneView& scene, const Intersector& accel, const MltStepParams& p,
                                uint64_t first, uint32_t n, float* importance, uint32_t* pixel, uint32_t* rays) {
    Vec2f pos[mltItemsPerLaunch<Intersector>()];
    tracePathsSideBySide<Intersector, MltProposalSampler<Store>>(
        scene, accel, p.path, n,
        [&](size_t l, MltProposalSampler<Store>& sampler) {
            sampler = MltProposalSampler<Store>(nullptr, 0, 0, mltBootstrapKey(p.seed, first + l), true, p.mutation);
            return primaryCameraRay(scene, sampler, p.width, p.height, pos[l]);
        },
        [&](size_t l, const MltProposalSampler<Store>&, const Spectrum& L, uint32_t traced) {
            pixel[l] = mltPixelOf(pos[l], p.width, p.height);
            importance[l] = mltImportance(mltValidRadiance(L), pos[l], p);
            rays[l] = traced;
        });
}

/// Starts `chain` at bootstrap sample i: stores its primary samples and re-traces it for F.
template <class Store, class Intersector>
CA_HD void startChain(const SceneView& scene, const Intersector& accel, const MltChainView<Store>& v,
                      const MltStepParams& p, uint32_t chain, uint64_t i, uint32_t& rays) {
    MltProposalSampler<Store> sampler(nullptr, 0, 0, mltBootstrapKey(p.seed, i), true, p.mutation);
    Vec2f pos;
    const Spectrum F = evaluatePrimarySample(scene, accel, sampler, p.path, p.width, p.height, pos, rays);
    const uint32_t used = min(sampler.dimension(), v.store.dims);
    for (uint32_t d = 0; d < used; ++d) v.store.set(chain, d, sampler.raw(d));
    v.usedDims[chain] = uint16_t(used);
    v.pos[chain] = pos;
    v.value[chain] = F;
    v.importance[chain] = mltImportance(F, pos, p);
}

/// Morton key of a chain's state for coherence sorting: film x, film y and the first bounce's
/// BSDF direction samples, 16 bits each, interleaved (Frolov & Galaktionov 2017, sec. 3.4).
template <class Store>
CA_HD uint64_t mltMortonKey(const MltChainView<Store>& v, uint32_t chain, int width, int height) {
    auto q16 = [](Float x) { return uint32_t(min(max(x, Float(0)), kOneMinusEpsilon) * 65536.0f); };
    uint32_t c[4] = {q16(v.pos[chain].x / Float(width)), q16(v.pos[chain].y / Float(height)), 0, 0};
    if (v.usedDims[chain] > kMltCameraDims + 5) {
        c[2] = q16(v.store.toFloat(v.store.get(chain, kMltCameraDims + 4), kMltCameraDims + 4));
        c[3] = q16(v.store.toFloat(v.store.get(chain, kMltCameraDims + 5), kMltCameraDims + 5));
    }
    uint64_t key = 0;
    for (int bit = 15; bit >= 0; --bit)
        for (int a = 0; a < 4; ++a) key = (key << 1) | ((c[a] >> bit) & 1u);
    return key;
}

}  // namespace caustica
