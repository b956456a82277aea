// sppm_driver.h — SppmDriver<Exec>: the one driver of both photon mappers (sppm, ppm) for the CPU
// and the GPU (launch.h). Each iteration:
//   eye pass      sppm: one camera path per pixel (Ld, visible points); ppm: only in the first
//                 iteration, `hitpoints` per pixel, kept for the whole render;
//   compaction    the entries that have a visible point, optionally in Morton order;
//   photon pass   direction "deposit": a lookup structure (spatial/) over the visible points'
//                 spheres (radii = their current radii, rebuilt every iteration), each photon adds
//                 into the spheres covering it with integer atomics; direction "gather": photons
//                 stored, optionally sorted by cell (Morton order), a structure over them, each
//                 visible point sums those within its radius; direction "auto": one of the two,
//                 chosen on the first passes (sppm_direction.h);
//   update        per entry (radius_schedule local or global).
// Sums are 64-bit fixed point (sppm_kernel.h), so both directions, every structure and every
// thread count give the same bits. The formulas are in sppm_kernel.h and sppm_photon.h.
//
// sppm_driver.cpp defines makeSppmDriver<DriverExec>: g++ compiles it for the CPU and
// cuda/*_driver.cu includes it so that nvcc compiles it for the GPU.
#pragma once

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/accel/device_scene.h"
#include "caustica/film/image.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/sppm/sppm_checkpoint.h"
#include "caustica/integrators/sppm/sppm_direction.h"
#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/integrators/sppm/sppm_order.h"
#include "caustica/integrators/sppm/sppm_passes.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/parallel/backend.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/scene/scene.h"
#include "caustica/spatial/brute_force.h"
#include "caustica/spatial/hash_grid.h"
#include "caustica/spatial/kd_tree.h"
#include "caustica/spatial/multi_hash.h"
#include "caustica/spatial/uniform_grid.h"
#include "caustica/util/error.h"

namespace caustica {

struct SppmStats {
    uint64_t iterations = 0;     // of the whole render (a loaded checkpoint's included)
    uint64_t photonPaths = 0;    // photon paths traced by this driver (not a checkpoint's)
    uint64_t rays = 0;           // closest-hit + shadow rays traced by this driver
    uint64_t visiblePoints = 0;  // visible points of the last iteration
    uint64_t storedPhotons = 0;  // direction gather: photons stored in the last iteration
    uint64_t photonRetraces = 0; // direction gather: photon passes traced again after an overflow
    double meanRadius = 0;       // mean radius after the last iteration (host develop/stat)
    size_t deviceBytes = 0;      // buffers of the driver + the last structure (scene not counted)
    size_t peakBytes = 0;        // the largest deviceBytes so far
    double eyeSeconds = 0, gridSeconds = 0, photonSeconds = 0, gatherSeconds = 0, updateSeconds = 0;
};

/// Host copies of what the last iteration's lookups were built over (bench/spatial_bench: the
/// point sets of real scenes): the visible points' positions and radii, and, with direction
/// "gather", the stored photons' positions (empty with "deposit", which stores no photon).
struct SppmLookupInputs {
    std::vector<Vec3f> photons;
    std::vector<Vec3f> visiblePoints;
    std::vector<Float> visibleRadii;
};

/// What the session sees of a driver (either device).
class SppmDriverBase {
public:
    virtual ~SppmDriverBase() = default;
    /// One iteration: tracePhotons(), then update().
    void iterate() {
        tracePhotons();
        update();
    }
    /// The first part of an iteration: the eye pass (sppm: every iteration; ppm: the first) and
    /// the photon pass of this driver's share of the photons (setPhotonShare), into the photon
    /// sums.
    virtual void tracePhotons() = 0;
    /// The second part: the progressive update of every entry from the photon sums (radii,
    /// flux), which clears them.
    virtual void update() = 0;
    /// Host copy of the photon sums of the iteration in flight (after tracePhotons(), before
    /// update()): per entry three 64-bit fixed-point flux sums, then per entry the photon count.
    /// Integer sums: adding those of disjoint photon shares gives the whole pass's to the bit.
    virtual std::vector<uint64_t> photonSums() const = 0;
    /// Replaces them (the sums over every share of the photons).
    virtual void setPhotonSums(const std::vector<uint64_t>& sums) = 0;
    /// Traces only the photons [first, first + count) of each iteration's photon_count (keyed by
    /// their global index, so the union of disjoint shares is the whole pass); the image stays
    /// normalised by photon_count. Default: all of them.
    void setPhotonShare(uint64_t first, uint64_t count) {
        if (first > settings_.photonCount || count > settings_.photonCount - first)
            throw Error("sppm: a photon share outside the iteration's photons");
        photonFirst_ = first;
        photonShare_ = count;
    }
    /// Direction "gather": sizes the photon store before the first photon pass for `photons`
    /// photons instead of the pilot's estimate (0: the pilot). A store that turns out too small is
    /// grown and the pass traced again with the same photons (stats().photonRetraces).
    void presizePhotonStore(uint64_t photons) { storePresize_ = photons; }
    /// Per pixel the mean over its entries of Ld / ldCount + τ / (iterations · photon_count · π R²).
    virtual Image develop() const = 0;
    /// Host copy of the statistics (row-major pixels, `entriesPerPixel()` entries each).
    virtual std::vector<SppmPixel> pixels() const = 0;
    /// Replaces the statistics and the iteration count (a checkpoint's).
    virtual void restore(const std::vector<SppmPixel>& pixels, uint64_t iterations) = 0;
    /// The point sets of the last iteration (empty before the first).
    virtual SppmLookupInputs lookupInputs() const = 0;
    const SppmStats& stats() const { return stats_; }
    const SppmSettings& settings() const { return settings_; }
    /// The photon pass's direction: settings().direction, or what "auto" chose (and why).
    const SppmDirectionChooser& direction() const { return direction_; }
    int width() const { return width_; }
    int height() const { return height_; }
    uint32_t entriesPerPixel() const { return settings_.mapper == PhotonMapper::Ppm ? settings_.hitpoints : 1; }

protected:
    SppmSettings settings_;
    SppmDirectionChooser direction_;
    SppmStats stats_;
    int width_ = 0, height_ = 0;
    uint64_t photonFirst_ = 0, photonShare_ = 0;  // the photons this driver traces per iteration
    uint64_t storePresize_ = 0;                     // presizePhotonStore
};

/// The driver for device Exec; throws caustica::Error for scenes it cannot render.
template <class Exec>
std::unique_ptr<SppmDriverBase> makeSppmDriver(const Scene& scene, const Accel& accel, const SppmSettings& settings,
                                               uint64_t seed);

/// The photon map's uniform grid has cells one largest radius wide (not the grid's default two):
/// a query box of 2-3 cells along an axis instead of 2 cells of twice the width, so about 0.56x
/// the candidates around a surface for 9 rows instead of 4 (PERFORMANCE.md, 2026-11-26, eye21).
inline constexpr Float kSppmGridCellRadii = 1;

/// Calls f(structure) with the lookup structure `kind` built over `points` on Exec's device.
template <class Exec, class F>
void withStructure(Exec exec, PhotonStructure kind, const PointSet& points, F&& f) {
    switch (kind) {
        case PhotonStructure::Grid: f(UniformGrid::build(exec, points, kSppmGridCellRadii)); return;
        case PhotonStructure::KdTree: f(KdTree::build(exec, points)); return;
        case PhotonStructure::MultiHash: f(MultiHash::build(exec, points)); return;
        case PhotonStructure::Brute: f(BruteForce::build(exec, points)); return;
        case PhotonStructure::Hash: f(HashGrid::build(exec, points)); return;
    }
}

template <class Exec>
class SppmDriver final : public SppmDriverBase {
public:
    SppmDriver(const Scene& scene, const Accel& accel, const SppmSettings& settings, uint64_t seed)
        : scene_(scene, accel, Exec::device()), seed_(seed) {
        settings_ = settings;
        direction_ = SppmDirectionChooser(settings.direction);
        width_ = scene.film.width;
        height_ = scene.film.height;
        const Float flux = maxEmissionFlux(scene.view());
        fixed_.scale = flux > 0 && std::isfinite(flux) ? 4294967296.0 / double(flux) : 1.0;
        const Bounds3f box = scene.bounds();
        boxLo_ = box.empty() ? Vec3f(0) : box.lo;
        emitterBoxes_ = buildEmitterBoxes(scene);
        const Vec3f extent = box.empty() ? Vec3f(1) : box.diagonal();
        boxInvExtent_ = Vec3f(extent.x > 0 ? 1 / extent.x : 1, extent.y > 0 ? 1 / extent.y : 1,
                              extent.z > 0 ? 1 / extent.z : 1);
        const size_t n = entryCount();
        if (n >= (size_t(1) << 32)) throw Error("sppm: too many pixels x hitpoints (at most 2^32 - 1)");
        const Device d = Exec::device();
        stats_buf_ = Buffer<SppmPixel>(d, n);
        points_ = Buffer<SppmVisiblePoint>(d, n);
        flags_ = Buffer<uint32_t>(d, n);
        list_ = Buffer<uint32_t>(d, n);
        keys_ = Buffer<uint32_t>(d, n);
        eyeRays_ = Buffer<uint32_t>(d, n);
        positions_ = Buffer<Vec3f>(d, n);
        radii_ = Buffer<Float>(d, n);
        phi_ = Buffer<uint64_t>(d, 3 * n);
        m_ = Buffer<uint64_t>(d, n);
        rayBlocks_ = Buffer<uint64_t>(d, size_t((settings_.photonCount + 1023) / 1024));
        counter_ = Buffer<uint64_t>(d, 1);
        photonShare_ = settings_.photonCount;
        if (!(settings_.initialRadius > 0)) settings_.initialRadius = autoRadius(scene);
        sppm_detail::initStats(Exec{}, n, double(settings_.initialRadius), stats_buf_.data(), phi_.data(), m_.data());
        bufferBytes_ = n * (sizeof(SppmPixel) + sizeof(SppmVisiblePoint) + 5 * sizeof(uint32_t) + sizeof(Vec3f) +
                            sizeof(Float) + 4 * sizeof(uint64_t)) +
                       rayBlocks_.size() * sizeof(uint64_t);
        noteBytes(bufferBytes_ + firstRadiance_.size() * sizeof(Spectrum));
        stats_.meanRadius = settings_.initialRadius;
    }

    void tracePhotons() override {
        using Clock = std::chrono::steady_clock;
        const uint64_t iteration = stats_.iterations;
        auto t0 = Clock::now();
        const bool ppm = settings_.mapper == PhotonMapper::Ppm;
        if (!ppm || !hitpointsReady_) {
            if (firstRadiance_.size() > 0) {
                // The automatic radius's eye pass was this iteration's (iteration 0, same streams).
                sppm_detail::addRadiance(Exec{}, entryCount(), firstRadiance_.data(), stats_buf_.data());
                dropFirstEyePass();
            } else {
                eyePass(iteration);
            }
            hitpointsReady_ = true;
            addLd_ = true;
        }
        const uint32_t count = visibleCount_;
        auto t1 = Clock::now();
        stats_.eyeSeconds += std::chrono::duration<double>(t1 - t0).count();
        if (count > 0) {
            sppm_detail::gatherPoints(Exec{}, count, list_.data(), points_.data(), stats_buf_.data(),
                                      positions_.data(), radii_.data());
            if (direction_.needsPilot()) pilotDirection(iteration, count);
            lastDirection_ = direction_.next();
            const auto t2 = Clock::now();
            if (lastDirection_ == PhotonDirection::Deposit)
                depositPass(iteration, count);
            else
                gatherPass(iteration, count);
            // GPU launches are asynchronous: a timed pass is timed to its last kernel's end.
            if (!direction_.decided()) detail::synchronizeOn(Exec::device());
            direction_.passed(std::chrono::duration<double>(Clock::now() - t2).count());
            // Auto chose deposit after a gather pass: the photon store is no longer needed.
            if (direction_.decided() && direction_.next() == PhotonDirection::Deposit && store_.size() > 0)
                releaseStore();
        }
        stats_.photonPaths += photonShare_;
    }

    void update() override {
        using Clock = std::chrono::steady_clock;
        auto t0 = Clock::now();
        sppm_detail::updateStats(Exec{}, entryCount(), double(settings_.alpha),
                                 settings_.radiusSchedule == RadiusSchedule::Global, stats_.iterations + 1, fixed_,
                                 stats_buf_.data(), phi_.data(), m_.data());
        ++stats_.iterations;
        stats_.updateSeconds += std::chrono::duration<double>(Clock::now() - t0).count();
    }

    std::vector<uint64_t> photonSums() const override {
        std::vector<uint64_t> sums = phi_.toHost();
        const std::vector<uint64_t> counts = m_.toHost();
        sums.insert(sums.end(), counts.begin(), counts.end());
        return sums;
    }
    void setPhotonSums(const std::vector<uint64_t>& sums) override {
        const size_t n = entryCount();
        if (sums.size() != 4 * n) throw Error("sppm: the photon sums do not fit the image");
        phi_.copyFromHost(std::vector<uint64_t>(sums.begin(), sums.begin() + std::ptrdiff_t(3 * n)));
        m_.copyFromHost(std::vector<uint64_t>(sums.begin() + std::ptrdiff_t(3 * n), sums.end()));
    }

    Image develop() const override {
        const std::vector<SppmPixel> p = pixels();
        double sum = 0;
        for (const SppmPixel& q : p) sum += q.radius;
        const_cast<SppmStats&>(stats_).meanRadius = p.empty() ? 0 : sum / double(p.size());
        const uint64_t ldCount = settings_.mapper == PhotonMapper::Ppm ? (stats_.iterations > 0 ? 1 : 0)
                                                                        : stats_.iterations;
        return sppmImage(p, width_, height_, entriesPerPixel(), stats_.iterations, settings_.photonCount, ldCount);
    }
    std::vector<SppmPixel> pixels() const override { return stats_buf_.toHost(); }
    void restore(const std::vector<SppmPixel>& pixels, uint64_t iterations) override {
        if (pixels.size() != entryCount()) throw Error("sppm: the statistics do not fit the image");
        stats_buf_.copyFromHost(pixels);
        stats_.iterations = iterations;
        dropFirstEyePass();  // resumed: the next eye pass is the checkpoint's next iteration's
        // ppm: the hitpoints are regenerated from the same streams; their Ld is in the statistics.
        hitpointsReady_ = false;
        addLd_ = settings_.mapper != PhotonMapper::Ppm || iterations == 0;
    }

    SppmLookupInputs lookupInputs() const override {
        SppmLookupInputs in;
        if (stats_.iterations == 0 && !hitpointsReady_) return in;
        in.visiblePoints = positions_.toHost();
        in.visibleRadii = radii_.toHost();
        in.visiblePoints.resize(visibleCount_);
        in.visibleRadii.resize(visibleCount_);
        if (lastDirection_ == PhotonDirection::Gather && photonPositions_.size() > 0) {
            in.photons = photonPositions_.toHost();
            in.photons.resize(size_t(stats_.storedPhotons));
        }
        return in;
    }

private:
    size_t entryCount() const { return size_t(width_) * size_t(height_) * entriesPerPixel(); }
    void noteBytes(size_t bytes) {
        stats_.deviceBytes = bytes;
        stats_.peakBytes = std::max(stats_.peakBytes, bytes);
    }

    /// `radiance`: where each entry's radiance goes instead of its Ld (EyeSampling::radiance).
    void eyePass(uint64_t iteration, Spectrum* radiance = nullptr) {
        const size_t n = entryCount();
        sppm_detail::EyeSampling sampling;
        sampling.perPixel = entriesPerPixel();
        sampling.iteration = iteration;
        sampling.fixedHitpoints = settings_.mapper == PhotonMapper::Ppm;
        sampling.addLd = addLd_;
        sampling.radiance = radiance;
        const SceneView& view = scene_.view();
        scene_.visit(Exec{}, [&](const auto& intersector) {
            sppm_detail::eyePass(Exec{}, view, intersector, settings_.path, settings_.roughnessThreshold,
                                 emitterBoxes_, seed_, sampling, width_, n, stats_buf_.data(), points_.data(), flags_.data(),
                                 eyeRays_.data());
        });
        stats_.rays += reduceSum(Exec::device(), Span<const uint32_t>(eyeRays_.data(), n));
        visibleCount_ = compactIndices(Exec::device(), Span<const uint32_t>(flags_.data(), n), list_.span());
        stats_.visiblePoints = visibleCount_;
        if (settings_.hitpointOrder != HitpointOrder::None && visibleCount_ > 1) {
            // Neighbouring visible points in neighbouring work items and memory (seed 003).
            sppm_detail::mortonKeys(Exec{}, visibleCount_, list_.data(), points_.data(), boxLo_, boxInvExtent_,
                                    keys_.data());
            radixSortPairs(Exec::device(), Span<uint32_t>(keys_.data(), visibleCount_),
                           Span<uint32_t>(list_.data(), visibleCount_), 30);
            if (settings_.hitpointOrder == HitpointOrder::Kmeans) clusterVisiblePoints();
        }
    }

    /// initial_radius 0: kSppmAutoFootprints pixel footprints at the median distance of the first
    /// iteration's visible points from the camera (the first iteration's eye pass, so the radius
    /// is the same on a resume and on any thread count); sppmAutoRadius (the scene's size) when
    /// no visible point is found. The first iteration then uses this eye pass (its visible points
    /// and, kept aside in firstRadiance_, its Ld) instead of tracing it again.
    Float autoRadius(const Scene& scene) {
        const auto t0 = std::chrono::steady_clock::now();
        firstRadiance_ = Buffer<Spectrum>(Exec::device(), entryCount());
        eyePass(0, firstRadiance_.data());
        stats_.eyeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (visibleCount_ == 0) return sppmAutoRadius(scene);
        sppm_detail::footprints(Exec{}, visibleCount_, list_.data(), points_.data(), scene_.view().camera,
                                width_, uint32_t(entriesPerPixel()), radii_.data());
        std::vector<Float> widths = radii_.toHost();
        widths.resize(visibleCount_);
        std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
        const Float r = kSppmAutoFootprints * widths[widths.size() / 2];
        return r > 0 && std::isfinite(r) ? r : sppmAutoRadius(scene);
    }

    /// sppm_order.h: Lloyd's k-means from the Morton chunks, then the list sorted by cluster.
    void clusterVisiblePoints() {
        const uint32_t count = visibleCount_;
        if (home_.size() == 0) {
            home_ = Buffer<uint32_t>(Exec::device(), entryCount());
            centres_ = Buffer<Vec3f>(Exec::device(), entryCount() / kKmeansClusterSize + 1);
            bufferBytes_ += home_.size() * sizeof(uint32_t) + centres_.size() * sizeof(Vec3f);
        }
        // keys_ (the Morton keys, no longer needed) holds each entry's cluster.
        kmeansOrder(Exec{}, count, list_.data(), points_.data(), home_.data(), keys_.data(), centres_.data());
    }

    void dropFirstEyePass() { firstRadiance_ = Buffer<Spectrum>(); }

    uint32_t photonDepth() const { return sppmMaxDepth(settings_.path, uint32_t(2 * kSppmDepthCap)); }
    SppmPhotonRules photonRules() const {
        return {settings_.path, photonDepth(), settings_.roughnessThreshold, settings_.photonRoulette};
    }

    void depositPass(uint64_t iteration, uint32_t count) {
        using Clock = std::chrono::steady_clock;
        auto t0 = Clock::now();
        const PointSet set{Span<const Vec3f>(positions_.data(), count), Span<const Float>(radii_.data(), count), 0};
        withStructure(Exec{}, settings_.structure, set, [&](const auto& structure) {
            noteBytes(bufferBytes_ + structure.memoryBytes());
            auto t1 = Clock::now();
            stats_.gridSeconds += std::chrono::duration<double>(t1 - t0).count();
            sppm_detail::zeroCounters(Exec{}, rayBlocks_.size(), rayBlocks_.data());
            const auto lookup = structure.view();
            const SceneView& view = scene_.view();
            scene_.visit(Exec{}, [&](const auto& intersector) {
                sppm_detail::depositPhotons(Exec{}, view, intersector, lookup, points_.data(), list_.data(),
                                            photonRules(), fixed_, seed_, iteration, photonFirst_, photonShare_,
                                            phi_.data(), m_.data(), rayBlocks_.data());
            });
            for (uint64_t r : rayBlocks_.toHost()) stats_.rays += r;
            stats_.photonSeconds += std::chrono::duration<double>(Clock::now() - t1).count();
        });
    }

    /// Traces the photon pass into the store, again with a larger store when it overflowed (the
    /// photon streams are keyed by (photon, iteration), so the second pass stores the same photons).
    /// With sort_photons the pass also writes each photon's Morton key and slot for the sort. The
    /// first store is sized by a pilot (pilotPhotonsPerPath), so that the first pass rarely overflows.
    uint64_t storePhotons(uint64_t iteration) {
        if (store_.size() == 0)
            resizeStore(storePresize_ > 0 ? size_t(storePresize_) : storeSizeFor(pilotPhotonsPerPath(iteration)));
        for (;;) {
            SppmPhotonStore store;
            store.photons = store_.data();
            store.capacity = uint64_t(store_.size());
            if (settings_.sortPhotons) {
                store.keys = photonKeys_.data();
                store.order = photonOrder_.data();
                store.lo = boxLo_;
                store.invExtent = boxInvExtent_;
            }
            const uint64_t stored = tracePhotonPaths(iteration, photonShare_, store);
            if (stored <= store_.size()) return stored;
            if (stored >= (uint64_t(1) << 32)) throw Error("sppm: more than 2^32 photons stored in one iteration");
            resizeStore(size_t(stored + stored / 4));
            ++stats_.photonRetraces;
        }
    }

    /// Traces the first `paths` photon paths of this driver's share into `store` (its counter is
    /// set here) and returns the photons they stored, those beyond its capacity included.
    uint64_t tracePhotonPaths(uint64_t iteration, uint64_t paths, SppmPhotonStore store) {
        sppm_detail::zeroCounters(Exec{}, 1, counter_.data());
        sppm_detail::zeroCounters(Exec{}, rayBlocks_.size(), rayBlocks_.data());
        store.counter = counter_.data();
        const SceneView& view = scene_.view();
        scene_.visit(Exec{}, [&](const auto& intersector) {
            sppm_detail::storePhotons(Exec{}, view, intersector, photonRules(), seed_, iteration, photonFirst_, paths,
                                      store, rayBlocks_.data());
        });
        for (uint64_t r : rayBlocks_.toHost()) stats_.rays += r;
        return counter_.toHost()[0];
    }

    /// The pilot: the first 1/64 of the share's photon paths (at least 4096) traced into a store
    /// of capacity 0, which counts their photons and keeps none; returns photons per path. The
    /// pilot's paths are the iteration's own, so it changes no photon. It sizes the first store
    /// (storeSizeFor): a 64th of a pass where a store sized by a fixed guess (2 photons a path;
    /// cornell-water stores 2.5) had the whole first pass traced again, without reserving 2
    /// photons a path for a scene that stores 0.05 (glass-caustic); and it tells direction "auto"
    /// how many photons a pass stores.
    double pilotPhotonsPerPath(uint64_t iteration) {
        const uint64_t pilot = std::min<uint64_t>(photonShare_, std::max<uint64_t>(photonShare_ / 64, 4096));
        if (pilot == 0) return 0;
        return double(tracePhotonPaths(iteration, pilot, SppmPhotonStore{})) / double(pilot);
    }
    /// The store for the share at `perPath` photons a path, plus a quarter.
    size_t storeSizeFor(double perPath) const {
        return size_t(std::max(1024.0, std::ceil(1.25 * perPath * double(photonShare_))));
    }

    /// Direction "auto" before its first pass: the pilot's photons against the `count` visible
    /// points (SppmDirectionChooser); a gather pass next finds its store sized by the same pilot.
    void pilotDirection(uint64_t iteration, uint32_t count) {
        const auto t0 = std::chrono::steady_clock::now();
        const double perPath = pilotPhotonsPerPath(iteration);
        direction_.pilot(perPath * double(photonShare_), count);
        if (direction_.next() == PhotonDirection::Gather && store_.size() == 0)
            resizeStore(storePresize_ > 0 ? size_t(storePresize_) : storeSizeFor(perPath));
        stats_.photonSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    /// The store and the arrays indexed like it (sort keys and order, sorted copy, positions).
    void resizeStore(size_t n) {
        const Device d = Exec::device();
        store_ = Buffer<SppmPhoton>(d, n);
        sorted_ = Buffer<SppmPhoton>(d, n);
        photonPositions_ = Buffer<Vec3f>(d, n);
        photonKeys_ = Buffer<uint32_t>(d, n);
        photonOrder_ = Buffer<uint32_t>(d, n);
    }
    void releaseStore() {
        store_ = Buffer<SppmPhoton>();
        sorted_ = Buffer<SppmPhoton>();
        photonPositions_ = Buffer<Vec3f>();
        photonKeys_ = Buffer<uint32_t>();
        photonOrder_ = Buffer<uint32_t>();
    }

    void gatherPass(uint64_t iteration, uint32_t count) {
        using Clock = std::chrono::steady_clock;
        auto t0 = Clock::now();
        const uint64_t stored = storePhotons(iteration);
        stats_.storedPhotons = stored;
        auto t1 = Clock::now();
        stats_.photonSeconds += std::chrono::duration<double>(t1 - t0).count();
        if (stored == 0) return;
        const size_t n = size_t(stored);
        const uint32_t* order = nullptr;
        if (settings_.sortPhotons) {
            // Photons of one cell next to each other in memory before the gather (seed 003); the
            // keys were written with the photons.
            radixSortPairs(Exec::device(), Span<uint32_t>(photonKeys_.data(), n),
                           Span<uint32_t>(photonOrder_.data(), n), 30);
            order = photonOrder_.data();
        }
        sppm_detail::arrangePhotons(Exec{}, n, store_.data(), order, sorted_.data(), photonPositions_.data());
        const Float largest = reduceMax(Exec::device(), Span<const float>(radii_.data(), count));
        const PointSet set{Span<const Vec3f>(photonPositions_.data(), n), Span<const Float>(), largest};
        withStructure(Exec{}, settings_.structure, set, [&](const auto& structure) {
            noteBytes(bufferBytes_ + structure.memoryBytes() +
                      store_.size() * (2 * sizeof(SppmPhoton) + sizeof(Vec3f) + 2 * sizeof(uint32_t)));
            auto t2 = Clock::now();
            stats_.gridSeconds += std::chrono::duration<double>(t2 - t1).count();
            sppm_detail::gatherPhotons(Exec{}, scene_.view(), structure.view(), sorted_.data(), points_.data(),
                                       list_.data(), count, radii_.data(), photonDepth(), fixed_, phi_.data(),
                                       m_.data());
            stats_.gatherSeconds += std::chrono::duration<double>(Clock::now() - t2).count();
        });
    }

    DeviceScene scene_;
    uint64_t seed_;
    SppmFixedPoint fixed_;
    Vec3f boxLo_, boxInvExtent_;
    EmitterBoxes emitterBoxes_;  // the eye pass's emission check (sppmEyePath)
    Buffer<SppmPixel> stats_buf_;
    Buffer<SppmVisiblePoint> points_;
    Buffer<uint32_t> flags_, list_, keys_, eyeRays_;
    Buffer<Vec3f> positions_;
    Buffer<Float> radii_;
    Buffer<uint64_t> phi_, m_, rayBlocks_, counter_;
    Buffer<Spectrum> firstRadiance_;  // autoRadius's eye pass = iteration 0's, until it is used
    // direction gather
    Buffer<SppmPhoton> store_, sorted_;
    Buffer<Vec3f> photonPositions_;
    Buffer<uint32_t> photonKeys_, photonOrder_;
    // hitpoint_order kmeans
    Buffer<uint32_t> home_;
    Buffer<Vec3f> centres_;
    uint32_t visibleCount_ = 0;
    PhotonDirection lastDirection_ = PhotonDirection::Gather;  // of the last photon pass
    bool hitpointsReady_ = false;
    bool addLd_ = true;
    size_t bufferBytes_ = 0;
};

}  // namespace caustica
