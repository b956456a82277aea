// mlt_buffers.h — the per-chain and per-pixel arrays every MLT driver keeps (on its device: host
// memory for the CPU driver, device memory for the GPU's), their kernel views, and the
// per-iteration bookkeeping both drivers share. The chains' stored primary samples are the
// drivers' own (their layouts differ).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "caustica/integrators/mlt/mlt_impl.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/primitives.h"

namespace caustica {

/// What one iteration's counters add up to (reduced where they live).
struct MltIterationCounts {
    uint64_t rays = 0, accepted = 0, largeSteps = 0;
    double largeStepSum = 0;
};

struct MltChainBuffers {
    Buffer<Vec2f> pos, proposalPos;
    Buffer<Spectrum> value, proposalValue;
    Buffer<float> importance, proposalImportance, largeStepSum, accum;
    Buffer<uint16_t> usedDims, proposalDims;
    Buffer<uint32_t> proposalRays, largeSteps, accepted, sortKeys, sortValues, pixelStart;
    // The splats of `batch` iterations, iteration t's n (k + 1) at slot t % batch; they are added
    // to `image` when the batch is full (mltTimedIteration).
    Buffer<MltSplat> splats;
    Buffer<double> image;  // kMltValuesPerPixel splat sums per pixel (chain, large-step layer), full batches
    uint32_t batch = 1;                // iterations per splat pass (mltSplatBatch)
    size_t splatsPerIteration = 0;     // n (k + 1)

    /// n chains with k proposals each on a film of `pixels` pixels, splats added to the image
    /// every `batch` iterations; the splat mode decides which scratch arrays exist. Splat sums
    /// start at zero.
    MltChainBuffers(const Device& device, uint32_t n, uint32_t k, uint32_t pixels, MltSplatKind splat, uint32_t batch)
        : pos(device, n),
          proposalPos(device, size_t(n) * k),
          value(device, n),
          proposalValue(device, size_t(n) * k),
          importance(device, n),
          proposalImportance(device, size_t(n) * k),
          largeStepSum(device, n),
          usedDims(device, n),
          proposalDims(device, size_t(n) * k),
          proposalRays(device, size_t(n) * k),
          largeSteps(device, n),
          accepted(device, n),
          splats(device, size_t(batch) * n * (k + 1)),
          image(device, size_t(kMltValuesPerPixel) * pixels),
          batch(batch),
          splatsPerIteration(size_t(n) * (k + 1)) {
        image.zero();
        if (splat == MltSplatKind::Atomic) {
            accum = Buffer<float>(device, size_t(kMltValuesPerPixel) * pixels);
            accum.zero();
        } else {
            sortKeys = Buffer<uint32_t>(device, splats.size());
            sortValues = Buffer<uint32_t>(device, splats.size());
            pixelStart = Buffer<uint32_t>(device, size_t(pixels) + 1);
        }
    }

    /// Bytes of everything but the chains' persistent state (proposals, splats, counters, image).
    size_t scratchBytes() const {
        return proposalPos.size() * (sizeof(Vec2f) + sizeof(Spectrum) + 2 * sizeof(float) + 2) +
               splats.size() * (sizeof(MltSplat) + 2 * sizeof(uint32_t)) + largeSteps.size() * 3 * sizeof(uint32_t) +
               image.size() * sizeof(double) + accum.size() * sizeof(float);
    }

    /// Iterations of an unfinished batch after `iterations` in all: their splats wait in the
    /// first slots.
    uint64_t pendingIterations(uint64_t iterations) const { return iterations % batch; }

    /// The kernels' view of iteration `iteration`: its splats go to slot iteration % batch.
    template <class Store>
    MltChainView<Store> view(const Store& store, uint64_t iteration = 0) {
        MltChainView<Store> v;
        v.store = store;
        v.chains = uint32_t(pos.size());
        v.pos = pos.data();
        v.value = value.data();
        v.importance = importance.data();
        v.usedDims = usedDims.data();
        v.proposalDims = proposalDims.data();
        v.proposalPos = proposalPos.data();
        v.proposalValue = proposalValue.data();
        v.proposalImportance = proposalImportance.data();
        v.proposalRays = proposalRays.data();
        v.splats = splats.data() + size_t(iteration % batch) * splatsPerIteration;
        v.largeStepSum = largeStepSum.data();
        v.largeSteps = largeSteps.data();
        v.accepted = accepted.data();
        return v;
    }

    /// The splat kernels' view of the first `iterations` slots, adding to `target` (the image's
    /// splat sums, or a copy of them).
    MltSplatView splatView(const MltFilm& film, int width, int height, uint64_t iterations, double* target) {
        MltSplatView v;
        v.width = width;
        v.height = height;
        v.eyeWidth = film.eyeWidth();
        v.filter = film.filter();
        v.footprint = film.filter().footprint();
        v.splats = splats.data();
        v.count = uint32_t(iterations * splatsPerIteration);
        v.accum = accum.data();
        v.sortedPixel = sortKeys.data();
        v.sortedSplat = sortValues.data();
        v.pixelStart = pixelStart.data();
        v.image = target;
        return v;
    }

    /// This iteration's counters, reduced on `device` (where the buffers live).
    MltIterationCounts reduceCounters(const Device& device) const {
        MltIterationCounts c;
        c.rays = reduceSum(device, proposalRays.constSpan());
        c.accepted = reduceSum(device, accepted.constSpan());
        c.largeSteps = reduceSum(device, largeSteps.constSpan());
        c.largeStepSum = reduceSum(device, largeStepSum.constSpan());
        return c;
    }
};

using MltClock = std::chrono::steady_clock;

/// Iterations whose splats are collected before one splat pass adds them to the image. A pass
/// also costs work per pixel (atomic: moving the iteration's float sums into the image; sort: a
/// first-splat search and a gather per pixel), which with few chains on a large image outweighed
/// the splats themselves (on a CPU, 1024 chains at 1024x1024: as long as tracing); a batch brings
/// at least a splat per pixel, at most kMltMaxBatchedSplats (the chains of a GPU, half a chain per
/// pixel by default, make batches of one iteration). settings.splatBatch > 0 sets it.
inline constexpr uint64_t kMltMaxBatchedSplats = uint64_t(1) << 22;
inline uint32_t mltSplatBatch(const MltSettings& settings, uint32_t pixels) {
    if (settings.splatBatch > 0) return settings.splatBatch;
    const uint64_t perIteration = uint64_t(settings.chains) * (uint64_t(settings.proposals) + 1);
    const uint64_t wanted = (uint64_t(pixels) + perIteration - 1) / perIteration;
    const uint64_t most = std::max<uint64_t>(1, kMltMaxBatchedSplats / perIteration);
    return uint32_t(std::clamp<uint64_t>(wanted, 1, most));
}

/// One iteration of every chain, its phases timed into `stats`: propose() traces the proposals,
/// advance() moves the chains (their splats into slot iterations % batch) and returns the
/// iteration's counters, splat() adds a full batch of splats to the image, sort() reorders the
/// chains (every settings.sortEvery iterations). The counters go into `stats`, the large steps
/// refine b. `secondsSince(t)` is the driver's clock (the GPU's waits for the device first).
/// Returns the rays traced.
template <class SecondsSince, class Propose, class Advance, class Splat, class Sort>
uint64_t mltTimedIteration(MltStats& stats, MltNormalisation& b, const MltSettings& settings, uint32_t batch,
                           SecondsSince secondsSince, Propose propose, Advance advance, Splat splat, Sort sort) {
    auto t = MltClock::now();
    propose();
    stats.traceSeconds += secondsSince(t);

    t = MltClock::now();
    const MltIterationCounts c = advance();
    stats.advanceSeconds += secondsSince(t);

    if ((stats.iterations + 1) % batch == 0) {
        t = MltClock::now();
        splat();
        stats.splatSeconds += secondsSince(t);
    }

    ++stats.iterations;
    stats.proposals += uint64_t(settings.chains) * settings.proposals;
    stats.accepted += c.accepted;
    stats.rays += c.rays;
    stats.largeSteps += c.largeSteps;
    b.add(c.largeStepSum, double(c.largeSteps));
    stats.b = b.b();

    if (settings.sortEvery > 0 && stats.iterations % settings.sortEvery == 0) {
        t = MltClock::now();
        sort();
        stats.sortSeconds += secondsSince(t);
    }
    return c.rays;
}

}  // namespace caustica
