// renderer.h — the render session: one object that renders a scene with any integrator on any
// device, to a budget, and carries the whole render in one checkpoint. The CLI, the Python module
// and an MPI driver are thin callers of it (render_run.h is the loop they share).
//
//     Renderer r(std::move(scene), request);
//     while (!r.finished()) r.step();
//     Image image = r.develop();
//
// Budgets (samples per pixel, seconds) count the whole render across resumes: a render resumed
// from a checkpoint (load) goes on with the time and samples it already has.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/distributed/communicator.h"
#include "caustica/film/aov_layers.h"
#include "caustica/film/image.h"
#include "caustica/parallel/device.h"
#include "caustica/render/checkpoint_envelope.h"
#include "caustica/render/integrator_session.h"
#include "caustica/render/render_request.h"
#include "caustica/scene/scene.h"

namespace caustica {

class AovSession;

/// Sets the film (and camera) to width x height pixels with the horizontal field of view kept,
/// dropping any crop window; throws caustica::Error for sizes outside 1..32768 per side or more
/// than 2^28 pixels.
void applyResolution(Scene& scene, int width, int height);

/// Figures of a render: seconds and samples per pixel of the whole render (every run), samples
/// and rays of this run.
struct RenderStats {
    double seconds = 0;
    uint64_t samples = 0;         // camera samples (MLT: proposals) of this run
    uint64_t rays = 0;            // rays traced in this run (closest hit + shadow)
    int samplesPerPixel = 0;      // samples (MLT: mutations, rounded) per pixel, whole render
    uint64_t invalidSamples = 0;  // NaN/Inf/negative samples dropped (whole render)
};

/// One rank's share of this run (Renderer::rankStats).
struct RankStats {
    uint64_t samples = 0, rays = 0;
    double seconds = 0;  // stepping, this run
};

struct RenderProgress {
    double samplesPerPixel = 0;  // so far, whole render
    double target = 0;           // samples per pixel wanted; 0 = none
    double seconds = 0;          // rendering time so far, whole render
    double timeLimit = 0;        // 0 = none
};

class Renderer {
public:
    /// Resolves `request` against `scene` (integrator, seed, resolution, device, budgets), builds
    /// the ray tracer and the integrator's session. `resumeFrom`: the header of the checkpoint
    /// this render will load, so that settings left to device-dependent defaults take the
    /// checkpoint's. Throws caustica::Error (one line) for anything that cannot run. `comm`: the
    /// ranks the render is spread over; every rank constructs its Renderer with the same scene
    /// and request and calls step() in lockstep (distributed/communicator.h).
    Renderer(Scene scene, const RenderRequest& request, const CheckpointHeader* resumeFrom = nullptr,
             Communicator& comm = singleProcess());
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const Scene& scene() const { return *scene_; }
    const std::string& integrator() const { return integrator_; }
    uint64_t seed() const { return seed_; }
    const Device& device() const { return device_; }
    Communicator& comm() const { return *comm_; }
    const char* accelName() const;
    /// The backend and, for Embree, its instruction-set cap and packet width (Accel::description).
    std::string accelDescription() const { return accel_->description(); }
    double accelBuildSeconds() const { return accelSeconds_; }
    /// Lines describing the render for its start ("scene: N triangles ...", "device: ...").
    std::string description() const;
    /// What a checkpoint of this render must agree on (render_identity.h).
    const RenderIdentity& identity() const { return identity_; }
    /// Things a user should know before waiting for the image (a scene without emitters).
    const std::vector<std::string>& warnings() const { return warnings_; }

    /// Whether the budget is spent (never before the integrator has an image).
    bool finished() const;
    /// One pass / iteration; its time counts towards the time budget.
    void step();
    RenderProgress progress() const;
    Image develop() const;
    /// Statistics of the render: seconds and samples per pixel of the whole render, samples and
    /// rays of this run (for rates, with runSeconds()), summed over the ranks. Collective when the
    /// render is spread over ranks (every rank calls it).
    RenderStats stats() const;
    /// Every rank's samples, rays and seconds of this run, by rank. Collective.
    std::vector<RankStats> rankStats() const;
    double runSeconds() const { return runSeconds_; }
    const IntegratorSession& session() const { return *session_; }
    /// Whether the render has AOVs (the scene's aov integrator or the request's), and their
    /// developed channels (aov_session.h).
    bool hasAovs() const { return aov_ != nullptr; }
    AovImage developAovs() const;

    /// Writes the whole state to `path` atomically (a temporary file, then a rename). Collective:
    /// every rank's session saves (gathering what the file needs) and rank 0 writes the file; a
    /// failure to write is every rank's (AgreedError).
    void save(const std::string& path) const;
    /// Restores a checkpoint written by save() for the same render; throws caustica::Error
    /// "PATH: REASON" naming the first setting that differs, leaving the render unchanged.
    /// Collective: rank 0 reads the file and broadcasts it, every rank restores from the same
    /// bytes; a checkpoint of another number of ranks is refused.
    void load(const std::string& path);

private:
    /// load() from a stream positioned at the checkpoint's start; errors name `path`.
    void loadFrom(const std::string& path, std::istream& in);

    std::unique_ptr<Scene> scene_;
    Communicator* comm_;
    std::unique_ptr<Accel> accel_;
    std::unique_ptr<IntegratorSession> session_;
    std::unique_ptr<AovSession> aov_;
    std::string integrator_;
    uint64_t seed_ = 0;
    Device device_;
    double accelSeconds_ = 0;
    RenderIdentity identity_;
    std::vector<std::string> warnings_;
    double targetSpp_ = 0, timeLimit_ = 0;
    double priorSeconds_ = 0;  // of earlier runs (resumed)
    double runSeconds_ = 0, lastStepSeconds_ = 0;
};

/// Reads the header of the checkpoint at `path`; throws caustica::Error "PATH: REASON".
CheckpointHeader readCheckpointHeaderFile(const std::string& path);

}  // namespace caustica
