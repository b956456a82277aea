// sppm_driver.h — SppmDriver<Exec>: the one SPPM driver for the CPU and the GPU (launch.h). Each
// iteration: eye pass (one camera path per pixel: Ld, visible points), compaction of the pixels
// that have a visible point, a spatial hash grid over their spheres (spatial/hash_grid.h, radii =
// the pixels' current radii, rebuilt every iteration), photon pass (deposits in 64-bit fixed
// point, integer atomics), per-pixel update. The formulas are in sppm_kernel.h.
//
// sppm_driver.cpp defines makeSppmDriver<DriverExec>: g++ compiles it for the CPU and
// cuda/*_driver.cu includes it so that nvcc compiles it for the GPU.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/accel/device_scene.h"
#include "caustica/film/image.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/scene/scene.h"
#include "caustica/spatial/hash_grid.h"

namespace caustica {

struct SppmStats {
    uint64_t iterations = 0;     // of the whole render (a loaded checkpoint's included)
    uint64_t photonPaths = 0;    // photon paths traced by this driver (not a checkpoint's)
    uint64_t rays = 0;           // closest-hit + shadow rays traced by this driver
    uint64_t visiblePoints = 0;  // visible points of the last iteration
    double meanRadius = 0;       // mean pixel radius after the last iteration (host develop/stat)
    size_t deviceBytes = 0;      // buffers of the driver + the last hash grid (scene not counted)
    double eyeSeconds = 0, gridSeconds = 0, photonSeconds = 0, updateSeconds = 0;
};

/// What the session sees of a driver (either device).
class SppmDriverBase {
public:
    virtual ~SppmDriverBase() = default;
    virtual void iterate() = 0;
    /// L = Ld / iterations + τ / (iterations · photon_count · π R²) per pixel.
    virtual Image develop() const = 0;
    /// Host copy of the per-pixel statistics (row-major).
    virtual std::vector<SppmPixel> pixels() const = 0;
    /// Replaces the statistics and the iteration count (a checkpoint's).
    virtual void restore(const std::vector<SppmPixel>& pixels, uint64_t iterations) = 0;
    const SppmStats& stats() const { return stats_; }
    const SppmSettings& settings() const { return settings_; }
    int width() const { return width_; }
    int height() const { return height_; }

protected:
    SppmSettings settings_;
    SppmStats stats_;
    int width_ = 0, height_ = 0;
};

/// The driver for device Exec; throws caustica::Error for scenes it cannot render (emitters
/// without an emission sampler: spot, directional, constant, envmap).
template <class Exec>
std::unique_ptr<SppmDriverBase> makeSppmDriver(const Scene& scene, const Accel& accel, const SppmSettings& settings,
                                               uint64_t seed);

/// The image of per-pixel statistics (host).
Image sppmImage(const std::vector<SppmPixel>& pixels, int width, int height, uint64_t iterations, uint64_t photons);

namespace sppm_detail {

template <class Exec, class Intersector>
void eyePass(Exec exec, const SceneView& view, const Intersector& accel, PathSettings path, uint64_t seed,
             uint64_t iteration, int width, size_t pixelCount, SppmPixel* pixels, SppmVisiblePoint* points,
             uint32_t* flags, uint32_t* rays) {
    launch(
        exec, "sppm.eye", pixelCount,
        [=] CA_HD(size_t p) {
            CameraSample c = cameraSample(view.camera, p, width, iteration, seed);
            SppmVisiblePoint vp;
            bool has = false;
            uint32_t count = 0;
            const Spectrum L =
                sppmEyePath(view, accel, c.sampler, c.ray, path, uint32_t(kSppmDepthCap), vp, has, count);
            // Invalid radiance (NaN/Inf/negative) is dropped as the film drops such samples.
            if (std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b) && L.r >= 0 && L.g >= 0 && L.b >= 0) {
                pixels[p].ld[0] += double(L.r);
                pixels[p].ld[1] += double(L.g);
                pixels[p].ld[2] += double(L.b);
            }
            vp.pixel = uint32_t(p);
            points[p] = vp;
            flags[p] = has ? 1u : 0u;
            rays[p] = count;
        },
        16);
}

template <class Exec>
void gatherPoints(Exec exec, size_t count, const uint32_t* list, const SppmVisiblePoint* points,
                  const SppmPixel* pixels, Vec3f* positions, Float* radii) {
    launch(exec, "sppm.points", count, [=] CA_HD(size_t j) {
        const uint32_t p = list[j];
        positions[j] = points[p].si.p;
        radii[j] = Float(pixels[p].radius);
    });
}

template <class Exec, class Intersector, class Lookup>
void photonPass(Exec exec, const SceneView& view, const Intersector& accel, const Lookup& lookup,
                const SppmVisiblePoint* points, const uint32_t* list, PathSettings path, uint32_t maxDepth,
                SppmFixedPoint fixed, uint64_t seed, uint64_t iteration, uint64_t photons, uint64_t* phi, uint64_t* m,
                uint64_t* rayBlocks) {
    launch(
        exec, "sppm.photons", size_t(photons),
        [=] CA_HD(size_t i) {
            IndependentSampler sampler = photonSampler(i, iteration, seed);
            uint32_t rays = 0;
            sppmTracePhoton(view, accel, lookup, points, list, sampler, path, maxDepth, fixed, phi, m, rays);
            sppmAtomicAdd(rayBlocks + i / 1024, rays);
        },
        16);
}

template <class Exec>
void updatePixels(Exec exec, size_t pixelCount, double alpha, SppmFixedPoint fixed, SppmPixel* pixels,
                  uint64_t* phi, uint64_t* m) {
    launch(exec, "sppm.update", pixelCount, [=] CA_HD(size_t p) {
        double flux[3];
        for (int c = 0; c < 3; ++c) {
            flux[c] = double(phi[3 * p + c]) / fixed.scale;
            phi[3 * p + c] = 0;
        }
        sppmUpdatePixel(pixels[p], flux, m[p], alpha);
        m[p] = 0;
    });
}

template <class Exec>
void initPixels(Exec exec, size_t pixelCount, double radius, SppmPixel* pixels, uint64_t* phi, uint64_t* m) {
    launch(exec, "sppm.init", pixelCount, [=] CA_HD(size_t p) {
        pixels[p] = SppmPixel{};
        pixels[p].radius = radius;
        for (int c = 0; c < 3; ++c) phi[3 * p + c] = 0;
        m[p] = 0;
    });
}

template <class Exec>
void zeroCounters(Exec exec, size_t n, uint64_t* counters) {
    launch(exec, "sppm.zero", n, [=] CA_HD(size_t i) { counters[i] = 0; });
}

}  // namespace sppm_detail

template <class Exec>
class SppmDriver final : public SppmDriverBase {
public:
    SppmDriver(const Scene& scene, const Accel& accel, const SppmSettings& settings, uint64_t seed)
        : scene_(scene, accel, Exec::device()), seed_(seed) {
        settings_ = settings;
        width_ = scene.film.width;
        height_ = scene.film.height;
        if (!(settings_.initialRadius > 0)) settings_.initialRadius = sppmAutoRadius(scene);
        const Float flux = maxEmissionFlux(scene.view());
        fixed_.scale = flux > 0 && std::isfinite(flux) ? 4294967296.0 / double(flux) : 1.0;
        const size_t n = pixelCount();
        const Device d = Exec::device();
        pixels_ = Buffer<SppmPixel>(d, n);
        points_ = Buffer<SppmVisiblePoint>(d, n);
        flags_ = Buffer<uint32_t>(d, n);
        list_ = Buffer<uint32_t>(d, n);
        eyeRays_ = Buffer<uint32_t>(d, n);
        positions_ = Buffer<Vec3f>(d, n);
        radii_ = Buffer<Float>(d, n);
        phi_ = Buffer<uint64_t>(d, 3 * n);
        m_ = Buffer<uint64_t>(d, n);
        rayBlocks_ = Buffer<uint64_t>(d, size_t((settings_.photonCount + 1023) / 1024));
        sppm_detail::initPixels(Exec{}, n, double(settings_.initialRadius), pixels_.data(), phi_.data(), m_.data());
        bufferBytes_ = n * (sizeof(SppmPixel) + sizeof(SppmVisiblePoint) + 4 * sizeof(uint32_t) + sizeof(Vec3f) +
                            sizeof(Float) + 4 * sizeof(uint64_t)) +
                       rayBlocks_.size() * sizeof(uint64_t);
        stats_.deviceBytes = bufferBytes_;
        stats_.meanRadius = settings_.initialRadius;
    }

    void iterate() override {
        using Clock = std::chrono::steady_clock;
        const size_t n = pixelCount();
        const uint64_t iteration = stats_.iterations;
        const PathSettings path = settings_.path;
        const SceneView& view = scene_.view();
        auto t0 = Clock::now();
        scene_.visit(Exec{}, [&](const auto& intersector) {
            sppm_detail::eyePass(Exec{}, view, intersector, path, seed_, iteration, width_, n, pixels_.data(),
                                 points_.data(), flags_.data(), eyeRays_.data());
        });
        stats_.rays += reduceSum(Exec::device(), Span<const uint32_t>(eyeRays_.data(), n));
        const uint32_t count = compactIndices(Exec::device(), Span<const uint32_t>(flags_.data(), n), list_.span());
        stats_.visiblePoints = count;
        auto t1 = Clock::now();
        stats_.eyeSeconds += std::chrono::duration<double>(t1 - t0).count();
        if (count > 0) {
            sppm_detail::gatherPoints(Exec{}, count, list_.data(), points_.data(), pixels_.data(), positions_.data(),
                                      radii_.data());
            PointSet set{Span<const Vec3f>(positions_.data(), count), Span<const Float>(radii_.data(), count), 0};
            const HashGrid grid = HashGrid::build(Exec{}, set);
            stats_.deviceBytes = bufferBytes_ + grid.memoryBytes();
            auto t2 = Clock::now();
            stats_.gridSeconds += std::chrono::duration<double>(t2 - t1).count();
            sppm_detail::zeroCounters(Exec{}, rayBlocks_.size(), rayBlocks_.data());
            const uint32_t maxDepth = sppmMaxDepth(path, uint32_t(2 * kSppmDepthCap));
            const auto lookup = grid.view();
            scene_.visit(Exec{}, [&](const auto& intersector) {
                sppm_detail::photonPass(Exec{}, view, intersector, lookup, points_.data(), list_.data(), path,
                                        maxDepth, fixed_, seed_, iteration, settings_.photonCount, phi_.data(),
                                        m_.data(), rayBlocks_.data());
            });
            for (uint64_t r : rayBlocks_.toHost()) stats_.rays += r;
            stats_.photonSeconds += std::chrono::duration<double>(Clock::now() - t2).count();
        }
        auto t3 = Clock::now();
        sppm_detail::updatePixels(Exec{}, n, double(settings_.alpha), fixed_, pixels_.data(), phi_.data(), m_.data());
        stats_.photonPaths += settings_.photonCount;
        ++stats_.iterations;
        stats_.updateSeconds += std::chrono::duration<double>(Clock::now() - t3).count();
    }

    Image develop() const override {
        const std::vector<SppmPixel> p = pixels();
        double sum = 0;
        for (const SppmPixel& q : p) sum += q.radius;
        const_cast<SppmStats&>(stats_).meanRadius = p.empty() ? 0 : sum / double(p.size());
        return sppmImage(p, width_, height_, stats_.iterations, settings_.photonCount);
    }
    std::vector<SppmPixel> pixels() const override { return pixels_.toHost(); }
    void restore(const std::vector<SppmPixel>& pixels, uint64_t iterations) override {
        if (pixels.size() != pixelCount()) throw Error("sppm: the statistics do not fit the image");
        pixels_.copyFromHost(pixels);
        stats_.iterations = iterations;
    }

private:
    size_t pixelCount() const { return size_t(width_) * size_t(height_); }

    DeviceScene scene_;
    uint64_t seed_;
    SppmFixedPoint fixed_;
    Buffer<SppmPixel> pixels_;
    Buffer<SppmVisiblePoint> points_;
    Buffer<uint32_t> flags_, list_, eyeRays_;
    Buffer<Vec3f> positions_;
    Buffer<Float> radii_;
    Buffer<uint64_t> phi_, m_, rayBlocks_;
    size_t bufferBytes_ = 0;
};

}  // namespace caustica
