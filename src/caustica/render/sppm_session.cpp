// sppm_session.cpp — the session of the photon mappers, sppm (stochastic progressive photon
// mapping) and ppm (progressive photon mapping): one iteration (eye pass — ppm: the first only —,
// photon pass, update) per step; samples per pixel = iterations; the checkpoint payload is every
// pixel's (ppm: hitpoint's) statistics and the iteration count (integrators/sppm/sppm_checkpoint.h).
//
// Over ranks (SessionContext::comm): each rank traces its share of every iteration's photons,
// chosen by global photon index (rank r: [r P / R, (r + 1) P / R) of P = photon_count), the eye
// pass the same on every rank; the photon sums (64-bit fixed point) are summed over the ranks
// before the update, so every rank applies the same update and holds the same state, and the
// image equals one process's to the bit (docs/MPI.md).
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "caustica/integrators/sppm/sppm_checkpoint.h"
#include "caustica/integrators/sppm/sppm_driver.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/parallel/backend.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica {
namespace {

/// The settings that change the image. Not among them: structure, direction, hitpoint_order and
/// sort_photons (the same sums to the bit, so a resume may change them) and max_passes (a budget).
RenderIdentity sppmIdentity(const SppmSettings& s) {
    RenderIdentity id = {identityEntry("max_depth", std::to_string(s.path.maxDepth)),
                         identityEntry("rr_depth", std::to_string(s.path.rrDepth)),
                         identityEntry("photon_roulette", photonRouletteName(s.photonRoulette)),
                         identityEntry("hide_emitters", s.path.hideEmitters ? "true" : "false"),
                         identityEntry("photon_count", std::to_string(s.photonCount)),
                         identityEntry("initial_radius", identityNumber(s.initialRadius)),
                         identityEntry("alpha", identityNumber(s.alpha)),
                         identityEntry("radius_schedule", radiusScheduleName(s.radiusSchedule)),
                         identityEntry("roughness_threshold", identityNumber(s.roughnessThreshold))};
    if (s.mapper == PhotonMapper::Ppm) id.push_back(identityEntry("hitpoints", std::to_string(s.hitpoints)));
    return id;
}

const char* mapperName(const SppmSettings& s) { return s.mapper == PhotonMapper::Ppm ? "ppm" : "sppm"; }

class SppmSession final : public IntegratorSession {
public:
    SppmSession(const SessionContext& c, const SppmSettings& settings) : device_(c.device), comm_(c.comm) {
        // --seed wins; else the integrator's seed; else the scene's sampler seed (c.seed).
        const uint64_t seed = c.request.seed || settings.seed < 0 ? c.seed : uint64_t(settings.seed);
        driver_ = onDevice(c.device, [&](auto exec) {
            return makeSppmDriver<decltype(exec)>(c.scene, c.accel, settings, seed);
        });
        seed_ = seed;
        const uint64_t photons = driver_->settings().photonCount, r = uint64_t(comm_.rank()),
                       ranks = uint64_t(comm_.size());
        const uint64_t first = photons * r / ranks;
        driver_->setPhotonShare(first, photons * (r + 1) / ranks - first);
    }

    void step(double) override {
        driver_->tracePhotons();
        if (comm_.size() > 1) {
            // Host copies (device buffers on a GPU), summed in rank order: integers, so exact.
            const uint64_t before = comm_.bytesSent();
            std::vector<uint64_t> sums = driver_->photonSums();
            comm_.sum(std::span<uint64_t>(sums));
            driver_->setPhotonSums(sums);
            bytesSentThisRun_ += comm_.bytesSent() - before;
        }
        driver_->update();
        ++iterationsThisRun_;
        if (recordEstimates_) makeStepEstimate();
    }
    double samplesPerPixel() const override { return double(driver_->stats().iterations); }
    uint64_t passLimit() const override { return driver_->settings().maxPasses; }
    bool hasImage() const override { return driver_->stats().iterations > 0; }
    Image develop() const override { return driver_->develop(); }
    SessionCounters counters() const override {
        // Every rank traces the eye pass: its camera samples count on rank 0 only, so that the
        // sum over ranks is one process's; rays are this rank's (eye pass and photon share).
        const uint64_t pixels = comm_.isRoot() ? uint64_t(driver_->width()) * uint64_t(driver_->height()) : 0;
        return SessionCounters{iterationsThisRun_ * pixels, driver_->stats().rays, 0};
    }
    RenderIdentity parameters() const override {
        RenderIdentity id = sppmIdentity(driver_->settings());
        id.push_back(identityEntry("photon_seed", std::to_string(seed_)));  // the streams' seed as used
        return id;
    }
    void save(std::ostream& out) const override { writeSppmCheckpoint(out, checkpoint(true)); }
    void load(std::istream& in) override {
        SppmCheckpoint c = readSppmCheckpoint(in, checkpoint(false));
        driver_->restore(c.pixels, c.iterations);
        if (recordEstimates_) cumulative_ = cumulativeEstimate();
    }
    bool hasStepEstimates() const override { return true; }
    void recordStepEstimates() override {
        recordEstimates_ = true;
        cumulative_ = cumulativeEstimate();
    }
    const Image* lastStepEstimate() const override { return estimate_.empty() ? nullptr : &estimate_; }
    std::string description() const override {
        const SppmSettings& s = driver_->settings();
        char line[256];
        std::snprintf(line, sizeof line,
                      "device: %s; integrator %s, %llu photons/iteration, initial radius %.4g, alpha %.4g, %s radius, "
                      "%s via %s",
                      deviceName(device_.kind), mapperName(s), (unsigned long long)s.photonCount,
                      double(s.initialRadius), double(s.alpha), radiusScheduleName(s.radiusSchedule),
                      photonDirectionName(s.direction), photonStructureName(s.structure));
        std::string text = line;
        if (s.mapper == PhotonMapper::Ppm) text += ", " + std::to_string(s.hitpoints) + " hitpoints/pixel";
        if (comm_.size() > 1) text += ", photons split over " + std::to_string(comm_.size()) + " ranks";
        return text;
    }
    void printSummary(std::FILE* out) const override {
        const SppmStats& s = driver_->stats();
        const double photonTime = s.photonSeconds > 0 ? s.photonSeconds : 1e-30;
        const char* name = mapperName(driver_->settings());
        std::fprintf(out, "%-11s %llu iterations, %llu photon paths this run (%.3g/s in the photon pass), "
                          "%llu visible points in the last iteration\n",
                     name, (unsigned long long)s.iterations, (unsigned long long)s.photonPaths,
                     double(s.photonPaths) / photonTime, (unsigned long long)s.visiblePoints);
        std::fprintf(out, "%-11s direction %s\n", name, driver_->direction().describe().c_str());
        if (s.storedPhotons > 0)
            std::fprintf(out, "%-11s %llu photons stored in the last gather pass, %llu passes traced again after an "
                              "overflow\n",
                         name, (unsigned long long)s.storedPhotons, (unsigned long long)s.photonRetraces);
        std::fprintf(out, "%-11s radius mean %.4g (initial %.4g); memory %s (peak %s)\n", name, s.meanRadius,
                     double(driver_->settings().initialRadius), formatBytes(s.deviceBytes).c_str(),
                     formatBytes(s.peakBytes).c_str());
        std::fprintf(out, "%-11s time eye %.3f s, structure %.3f s, photons %.3f s, gather %.3f s, update %.3f s\n",
                     name, s.eyeSeconds, s.gridSeconds, s.photonSeconds, s.gatherSeconds, s.updateSeconds);
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
                {"sppm_peak_device_bytes", std::to_string(s.peakBytes)},
                {"sppm_stored_photons", std::to_string(s.storedPhotons)},
                // gather or deposit (what auto chose; "auto" while it is still timing both)
                {"sppm_direction", std::string("\"") + photonDirectionName(driver_->direction().current()) + "\""},
                {"sppm_gather_seconds", identityNumber(s.gatherSeconds)},
                {"sppm_eye_seconds", identityNumber(s.eyeSeconds)},
                {"sppm_grid_seconds", identityNumber(s.gridSeconds)},
                {"sppm_photon_seconds", identityNumber(s.photonSeconds)},
                {"sppm_update_seconds", identityNumber(s.updateSeconds)},
                {"sppm_ranks", std::to_string(comm_.size())},
                {"bytes_sent", std::to_string(comm_.bytesSent())},  // this rank's, whole run
                {"bytes_sent_per_iteration",
                 identityNumber(iterationsThisRun_ > 0 ? double(bytesSentThisRun_) / double(iterationsThisRun_) : 0.0)}};
    }

private:
    /// Per pixel and RGB channel, `iterations` times the developed image (sppmPixelRadiance): sppm
    /// Σ_i Ld_i + τ / (photon_count · π R²), ppm iterations · Ld + τ / (photon_count · π R²). As
    /// τ / (π R²) is the sum over iterations of Phi_i / (π R_i²) (sppm_kernel.h, both radius
    /// schedules), its growth over one iteration is that iteration's own estimate,
    /// Ld_i + Phi_i / (photon_count · π R_i²): the batch of the variance AOV (docs/AOV.md).
    std::vector<double> cumulativeEstimate() const {
        const std::vector<SppmPixel> entries = driver_->pixels();
        const uint32_t perPixel = driver_->entriesPerPixel();
        const uint64_t iterations = driver_->stats().iterations, photons = driver_->settings().photonCount;
        const uint64_t ldCount = driver_->settings().mapper == PhotonMapper::Ppm ? 1 : iterations;
        const size_t pixels = entries.size() / perPixel;
        std::vector<double> sum(3 * pixels, 0.0);
        for (size_t p = 0; p < pixels; ++p)
            for (uint32_t j = 0; j < perPixel; ++j) {
                double L[3];
                sppmPixelRadiance(entries[p * perPixel + j], iterations, photons, ldCount, L);
                for (int c = 0; c < 3; ++c) sum[3 * p + size_t(c)] += L[c] * double(iterations) / double(perPixel);
            }
        return sum;
    }
    void makeStepEstimate() {
        std::vector<double> now = cumulativeEstimate();
        if (estimate_.empty()) estimate_ = Image(driver_->width(), driver_->height());
        for (size_t i = 0; i < now.size(); ++i) estimate_.rgb[i] = float(now[i] - cumulative_[i]);
        cumulative_ = std::move(now);
    }

    SppmCheckpoint checkpoint(bool withState) const {
        SppmCheckpoint c;
        const SppmSettings& s = driver_->settings();
        c.width = driver_->width();
        c.height = driver_->height();
        c.perPixel = driver_->entriesPerPixel();
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
    Communicator& comm_;
    uint64_t bytesSentThisRun_ = 0;  // by the exchanges of step(), this run
    uint64_t seed_ = 0;
    std::unique_ptr<SppmDriverBase> driver_;
    uint64_t iterationsThisRun_ = 0;
    bool recordEstimates_ = false;
    std::vector<double> cumulative_;  // cumulativeEstimate() after the last step (or load)
    Image estimate_;                  // the last step's batch estimate
};

}  // namespace

std::unique_ptr<IntegratorSession> makeSppmSession(const SessionContext& c) {
    return std::make_unique<SppmSession>(c, readSppmSettings(c.params, PhotonMapper::Sppm));
}
std::unique_ptr<IntegratorSession> makePpmSession(const SessionContext& c) {
    return std::make_unique<SppmSession>(c, readSppmSettings(c.params, PhotonMapper::Ppm));
}

namespace {
std::string describePhotonMapper(IntegratorParams& params, PhotonMapper mapper) {
    const SppmSettings s = readSppmSettings(params, mapper);
    std::string line;
    for (const IdentityEntry& e : sppmIdentity(s)) line += (line.empty() ? "" : ", ") + e.name + " " + e.value;
    line += std::string(", structure ") + photonStructureName(s.structure) + ", direction " +
            photonDirectionName(s.direction) + ", max_passes " + std::to_string(s.maxPasses);
    return line + " (initial_radius 0: 3 pixel footprints at the median visible-point distance; max_passes 0: the sample count)";
}
}  // namespace

std::string describeSppm(IntegratorParams& params) { return describePhotonMapper(params, PhotonMapper::Sppm); }
std::string describePpm(IntegratorParams& params) { return describePhotonMapper(params, PhotonMapper::Ppm); }

}  // namespace caustica
