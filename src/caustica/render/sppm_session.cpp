// sppm_session.cpp — the session of stochastic progressive photon mapping: one iteration (eye
// pass, photon pass, per-pixel update) per step; samples per pixel = iterations; the checkpoint
// payload is every pixel's statistics and the iteration count (integrators/sppm/sppm_checkpoint.h).
#include <cstdio>
#include <memory>
#include <string>

#include "caustica/integrators/sppm/sppm_checkpoint.h"
#include "caustica/integrators/sppm/sppm_driver.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/parallel/backend.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica {
namespace {

RenderIdentity sppmIdentity(const SppmSettings& s) {
    return {identityEntry("max_depth", std::to_string(s.path.maxDepth)),
            identityEntry("rr_depth", std::to_string(s.path.rrDepth)),
            identityEntry("hide_emitters", s.path.hideEmitters ? "true" : "false"),
            identityEntry("photon_count", std::to_string(s.photonCount)),
            identityEntry("initial_radius", identityNumber(s.initialRadius)),
            identityEntry("alpha", identityNumber(s.alpha))};
}

class SppmSession final : public IntegratorSession {
public:
    SppmSession(const SessionContext& c, const SppmSettings& settings) : device_(c.device) {
        driver_ = onDevice(c.device, [&](auto exec) {
            return makeSppmDriver<decltype(exec)>(c.scene, c.accel, settings, c.seed);
        });
    }

    void step(double) override {
        driver_->iterate();
        ++iterationsThisRun_;
    }
    double samplesPerPixel() const override { return double(driver_->stats().iterations); }
    bool hasImage() const override { return driver_->stats().iterations > 0; }
    Image develop() const override { return driver_->develop(); }
    SessionCounters counters() const override {
        const uint64_t pixels = uint64_t(driver_->width()) * uint64_t(driver_->height());
        return SessionCounters{iterationsThisRun_ * pixels, driver_->stats().rays, 0};
    }
    RenderIdentity parameters() const override { return sppmIdentity(driver_->settings()); }
    void save(std::ostream& out) const override { writeSppmCheckpoint(out, checkpoint(true)); }
    void load(std::istream& in) override {
        SppmCheckpoint c = readSppmCheckpoint(in, checkpoint(false));
        driver_->restore(c.pixels, c.iterations);
    }
    std::string description() const override {
        const SppmSettings& s = driver_->settings();
        char line[256];
        std::snprintf(line, sizeof line, "device: %s; integrator sppm, %llu photons/iteration, initial radius %.4g, alpha %.4g",
                      deviceName(device_.kind), (unsigned long long)s.photonCount, double(s.initialRadius),
                      double(s.alpha));
        return line;
    }
    void printSummary(std::FILE* out) const override {
        const SppmStats& s = driver_->stats();
        const double photonTime = s.photonSeconds > 0 ? s.photonSeconds : 1e-30;
        std::fprintf(out, "sppm        %llu iterations, %llu photon paths this run (%.3g/s in the photon pass), "
                          "%llu visible points in the last iteration\n",
                     (unsigned long long)s.iterations, (unsigned long long)s.photonPaths,
                     double(s.photonPaths) / photonTime, (unsigned long long)s.visiblePoints);
        std::fprintf(out, "sppm radius mean %.4g (initial %.4g); memory %s\n", s.meanRadius,
                     double(driver_->settings().initialRadius), formatBytes(s.deviceBytes).c_str());
        std::fprintf(out, "sppm time   eye %.3f s, grid %.3f s, photons %.3f s, update %.3f s\n", s.eyeSeconds,
                     s.gridSeconds, s.photonSeconds, s.updateSeconds);
    }
    std::vector<std::pair<std::string, std::string>> statsJson() const override {
        const SppmStats& s = driver_->stats();
        return {{"sppm_iterations", std::to_string(s.iterations)},
                {"sppm_photon_paths", std::to_string(s.photonPaths)},
                {"sppm_photon_paths_per_second",
                 identityNumber(s.photonSeconds > 0 ? double(s.photonPaths) / s.photonSeconds : 0.0)},
                {"sppm_visible_points", std::to_string(s.visiblePoints)},
                {"sppm_mean_radius", identityNumber(s.meanRadius)},
                {"sppm_device_bytes", std::to_string(s.deviceBytes)},
                {"sppm_eye_seconds", identityNumber(s.eyeSeconds)},
                {"sppm_grid_seconds", identityNumber(s.gridSeconds)},
                {"sppm_photon_seconds", identityNumber(s.photonSeconds)},
                {"sppm_update_seconds", identityNumber(s.updateSeconds)}};
    }

private:
    SppmCheckpoint checkpoint(bool withState) const {
        SppmCheckpoint c;
        const SppmSettings& s = driver_->settings();
        c.width = driver_->width();
        c.height = driver_->height();
        c.photonCount = s.photonCount;
        c.alpha = double(s.alpha);
        c.initialRadius = double(s.initialRadius);
        if (withState) {
            c.iterations = driver_->stats().iterations;
            c.pixels = driver_->pixels();
        }
        return c;
    }

    Device device_;
    std::unique_ptr<SppmDriverBase> driver_;
    uint64_t iterationsThisRun_ = 0;
};

}  // namespace

std::unique_ptr<IntegratorSession> makeSppmSession(const SessionContext& c) {
    return std::make_unique<SppmSession>(c, readSppmSettings(c.params));
}

std::string describeSppm(IntegratorParams& params) {
    std::string line;
    for (const IdentityEntry& e : sppmIdentity(readSppmSettings(params)))
        line += (line.empty() ? "" : ", ") + e.name + " " + e.value;
    return line + " (initial_radius 0: 3 x scene diagonal / image size)";
}

}  // namespace caustica
