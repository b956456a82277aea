#include "caustica/render/renderer.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "caustica/distributed/agreed_error.h"
#include "caustica/distributed/launch_environment.h"
#include "caustica/parallel/backend.h"
#include "caustica/parallel/device_select.h"
#include "caustica/render/aov_session.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/render/render_denoise.h"
#include "caustica/util/atomic_file.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The scene's part of the identity: input files by content, -D values, film size and crop.
RenderIdentity sceneIdentity(const Scene& scene, const RenderRequest& request, uint64_t seed, int ranks) {
    RenderIdentity id;
    // A scene built in memory (tests, scripts) has no file: its arrays are the caller's business.
    id.push_back(scene.sourceFile.empty() ? identityEntry("scene file", "none (built in memory)")
                                          : fileIdentityEntry("scene file", scene.sourceFile));
    std::vector<std::string> seen{scene.sourceFile};
    for (const std::string& file : scene.inputFiles) {
        if (std::find(seen.begin(), seen.end(), file) != seen.end()) continue;
        seen.push_back(file);
        id.push_back(fileIdentityEntry("input file", file));
    }
    std::string defines;
    for (const auto& [name, value] : request.defines) defines += (defines.empty() ? "" : ", ") + name + "=" + value;
    id.push_back(identityEntry("-D values", defines.empty() ? "none" : defines));
    id.push_back(identityEntry("resolution", std::to_string(scene.film.width) + "x" + std::to_string(scene.film.height)));
    const Camera& c = scene.camera;
    id.push_back(identityEntry("crop window", "at " + std::to_string(c.cropX) + "," + std::to_string(c.cropY) + " of " +
                                                  std::to_string(c.width) + "x" + std::to_string(c.height)));
    id.push_back(identityEntry("seed", std::to_string(seed)));
    // Only a stereo render names its rig, so mono checkpoints of earlier versions still resume.
    if (request.stereo.mode != StereoMode::Off) id.push_back(stereoIdentityEntry(request.stereo));
    if (ranks > 1) id.push_back(ranksIdentityEntry(ranks));  // likewise: only a render over ranks
    return id;
}

/// The GPU of this process: the request's, else under an MPI launcher the local rank's (one GPU
/// per rank, round robin when a host has more ranks than GPUs), else the CUDA default.
void chooseGpu(const RenderRequest& request, const Communicator& comm, int gpuCount) {
    int index = request.gpu;
    if (index < 0 && comm.size() > 1 && gpuCount > 0) {
        const int local = localRankFromEnvironment();
        index = (local >= 0 ? local : comm.rank()) % gpuCount;
    }
    if (index >= 0) selectGpu(index);
}

}  // namespace

void applyResolution(Scene& scene, int w, int h) {
    if (w <= 0 || h <= 0 || w > 32768 || h > 32768 || int64_t(w) * h > (int64_t(1) << 28))
        throw Error("absurd resolution " + std::to_string(w) + "x" + std::to_string(h) +
                    " (each side 1..32768, at most 268435456 pixels)");
    // Keeps the horizontal field of view (Mitsuba's default fov_axis="x").
    scene.camera.tanHalfY = scene.camera.tanHalfX * Float(h) / Float(w);
    scene.camera.width = scene.film.width = w;
    scene.camera.height = scene.film.height = h;
    scene.camera.cropX = scene.camera.cropY = 0;  // the whole image at the new size, no crop
}

Renderer::Renderer(Scene scene, const RenderRequest& request, const CheckpointHeader* resumeFrom,
                   Communicator& comm)
    : scene_(std::make_unique<Scene>(std::move(scene))), comm_(&comm) {
    Scene& s = *scene_;
    reserveVertexPadding(s);  // a copied Scene (the Python module's) has none: Embree then shares
    if (request.resolution) applyResolution(s, request.resolution->first, request.resolution->second);
    applyStereo(s, request.stereo);  // after the resolution: the rig doubles the film's width
    integrator_ = request.integrator.empty() ? s.integrator.type : request.integrator;
    const IntegratorEntry& entry = findIntegrator(integrator_);
    IntegratorParams params = integratorParams(s.integrator, integrator_, request.integratorParams);
    seed_ = request.seed ? *request.seed : s.seed;
    if (!(request.timeLimit >= 0) || !std::isfinite(request.timeLimit))
        throw Error("the time budget must be a finite number of seconds");
    timeLimit_ = request.timeLimit;
    targetSpp_ = request.samplesPerPixel > 0 ? request.samplesPerPixel : (timeLimit_ > 0 ? 0 : s.sampleCount);

    // The device: `cuda` without a GPU fails here; `auto` falls back to the CPU for what the GPU
    // does not run.
    const DeviceAvailability available = currentDeviceAvailability();
    device_ = Device{selectDevice(request.device, available)};
    if (request.gpu >= 0 && device_.isCpu()) throw Error("--gpu needs --device cuda (or auto with a GPU)");
    if (!device_.isCpu()) {
        IntegratorParams probe = params;
        if (const std::string refusal = entry.gpuRefusal(probe); !refusal.empty()) {
            if (request.device != "auto") throw Error(refusal);
            device_ = Device::cpu();
        }
    }
    if (!device_.isCpu()) chooseGpu(request, comm, available.gpuCount);
    const AccelKind accelKind = device_.isCpu() ? request.accel : AccelKind::Bvh;  // a GPU traces the own BVH
    if (s.lights.empty())
        warnings_.push_back(s.sourceFile + ": the scene has no emitter: the image will be black");
    identity_ = sceneIdentity(s, request, seed_, comm.size());
    const auto buildStart = Clock::now();
    EmbreeSceneOptions embreeOptions;
    embreeOptions.isa = request.embreeIsa;
    accel_ = std::make_unique<Accel>(s, accelKind, BvhBuildOptions{}, embreeOptions);
    accelSeconds_ = secondsSince(buildStart);
    const SessionContext context{s, *accel_, device_, seed_, request, params,
                                 resumeFrom ? &resumeFrom->identity : nullptr, comm};
    session_ = entry.make(context);
    // An integrator's own pass count (max_passes) replaces the scene's sample count, and caps a
    // time budget, unless the request names a sample count.
    if (request.samplesPerPixel <= 0)
        if (const uint64_t limit = session_->passLimit(); limit > 0) targetSpp_ = double(limit);
    for (std::string& w : params.unread()) warnings_.push_back(std::move(w));
    for (IdentityEntry& e : session_->parameters()) identity_.push_back(std::move(e));
    // AOVs: the command line's list, else the scene's aov integrator's. Part of the identity, so
    // a resume never drops or restarts them. A stereo render's AOVs cover both eyes (the AOV pass
    // takes the same per-eye camera samples; its film stops the filter at the seam).
    const bool aovsFromRequest = !request.aovs.empty();
    if (aovsFromRequest || !s.integrator.aovs.empty() || request.denoiseGuides) {
        const std::string where = request.denoiseGuides && !aovsFromRequest && s.integrator.aovs.empty()
                                      ? "--denoise"
                                      : aovsFromRequest ? "--aov" : s.integrator.aovsWhere;
        // The AOV session takes this rank's pass only; the ranks' AOVs are not gathered yet.
        if (comm.size() > 1)
            throw Error(where + ": AOVs (and the denoiser's guides) of a render over several MPI ranks are not "
                        "supported");
        AovSpec spec = aovsFromRequest ? parseAovSpec(request.aovs, "--aov")
                       : !s.integrator.aovs.empty() ? parseAovSpec(s.integrator.aovs, s.integrator.aovsWhere)
                                                    : AovSpec{};
        if (request.denoiseGuides) spec = withDenoiseGuides(std::move(spec), session_->rendersPixelPasses() || session_->hasStepEstimates());
        aov_ = std::make_unique<AovSession>(s, *accel_, device_, seed_, spec, *session_, integrator_);
        identity_.push_back(identityEntry("aovs", spec.text()));
    }
}

Renderer::~Renderer() = default;

const char* Renderer::accelName() const { return accelKindName(accel_->kind()); }

std::string Renderer::description() const {
    const Scene& s = *scene_;
    char line[512];
    std::snprintf(line, sizeof line, "%s: %zu triangles, %zu spheres, %zu lights; %dx%d; %s built in %s\n",
                  s.sourceFile.c_str(), s.triangles.size(), s.spheres.size(), s.lights.size(), s.film.width,
                  s.film.height, accel_->description().c_str(), ProgressReporter::formatDuration(accelSeconds_).c_str());
    return line + session_->description() + "\n";
}

bool Renderer::finished() const {
    if (!session_->hasImage()) return false;
    if (targetSpp_ > 0 && session_->samplesPerPixel() >= targetSpp_) return true;
    if (timeLimit_ > 0) {
        // Stop when the next step would most likely overrun the budget by more than half a step.
        const double t = priorSeconds_ + runSeconds_;
        if (t >= timeLimit_ || t + 0.5 * lastStepSeconds_ > timeLimit_) return true;
    }
    return false;
}

void Renderer::step() {
    const auto start = Clock::now();
    const double samplesBefore = session_->samplesPerPixel();
    session_->step(targetSpp_ > 0 ? targetSpp_ - samplesBefore : 0);
    if (aov_) aov_->afterStep(*session_, samplesBefore);
    lastStepSeconds_ = secondsSince(start);
    runSeconds_ += lastStepSeconds_;
}

RenderProgress Renderer::progress() const {
    return RenderProgress{session_->samplesPerPixel(), targetSpp_, priorSeconds_ + runSeconds_, timeLimit_};
}

Image Renderer::develop() const { return session_->develop(); }

AovImage Renderer::developAovs() const { return aov_ ? aov_->develop() : AovImage{}; }

RenderStats Renderer::stats() const {
    if (comm_->size() > 1) session_->gatherStatistics();  // collective, as the sum below
    const SessionCounters c = session_->counters();
    RenderStats s;
    s.seconds = priorSeconds_ + runSeconds_;
    s.samples = c.samples;
    s.rays = c.rays + (aov_ ? aov_->rays() : 0);
    s.samplesPerPixel = int(std::lround(session_->samplesPerPixel()));
    s.invalidSamples = c.invalidSamples;
    if (comm_->size() > 1) {  // samples and rays are this rank's: the render's are the sum
        uint64_t counts[2] = {s.samples, s.rays};
        comm_->sum(std::span<uint64_t>(counts));
        s.samples = counts[0];
        s.rays = counts[1];
    }
    return s;
}

std::vector<RankStats> Renderer::rankStats() const {
    const SessionCounters c = session_->counters();
    const RankStats mine{c.samples, c.rays + (aov_ ? aov_->rays() : 0), runSeconds_};
    std::vector<RankStats> all;
    for (const std::vector<uint8_t>& bytes :
         comm_->allGather(std::span(reinterpret_cast<const uint8_t*>(&mine), sizeof mine))) {
        RankStats r;
        std::memcpy(&r, bytes.data(), std::min(bytes.size(), sizeof r));
        all.push_back(r);
    }
    return all;
}

void Renderer::save(const std::string& path) const {
    CheckpointHeader header{integrator_, identity_, priorSeconds_ + runSeconds_, session_->samplesPerPixel()};
    auto writeState = [&](std::ostream& out) {
        writeCheckpointHeader(out, header);
        session_->save(out);
        if (aov_) aov_->save(out);
    };
    if (comm_->size() == 1) return writeFileAtomically(path, writeState);
    // Every rank's session saves (it may gather its ranks' state to rank 0); rank 0 writes.
    std::ostringstream state(std::ios::binary);
    writeState(state);
    agreeOnFailure(*comm_, [&] {
        if (comm_->isRoot()) writeFileAtomically(path, [&](std::ostream& out) { out << state.str(); });
    });
}

CheckpointHeader readCheckpointHeaderFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot read the checkpoint");
    try {
        return readCheckpointHeader(in);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
}

void Renderer::load(const std::string& path) {
    if (comm_->size() == 1) {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw Error(path + ": cannot read the checkpoint");
        return loadFrom(path, in);
    }
    // Rank 0 reads the file, every rank restores from its bytes: the same bytes give every rank
    // the same outcome, so a refusal is every rank's (AgreedError) and ends them together.
    std::vector<uint8_t> bytes;
    agreeOnFailure(*comm_, [&] {
        if (!comm_->isRoot()) return;
        std::ifstream in(path, std::ios::binary);
        if (!in) throw Error(path + ": cannot read the checkpoint");
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    });
    comm_->broadcast(bytes, 0);
    std::istringstream in(std::string(bytes.begin(), bytes.end()), std::ios::binary);
    try {
        loadFrom(path, in);
    } catch (const Error& e) {
        throw AgreedError(e.what());
    }
}

void Renderer::loadFrom(const std::string& path, std::istream& in) {
    CheckpointHeader header;
    try {
        header = readCheckpointHeader(in);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    if (const std::string ranks = rankCountMismatch(header.identity, comm_->size()); !ranks.empty())
        throw Error(path + ": " + ranks);
    if (const std::string mismatch = checkpointMismatch(header, integrator_, identity_); !mismatch.empty())
        throw Error(path + ": " + mismatch);
    try {
        session_->load(in);
        if (aov_) aov_->load(in, session_->samplesPerPixel());
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    if (std::abs(session_->samplesPerPixel() - header.samplesPerPixel) > 1e-6 * std::max(1.0, header.samplesPerPixel))
        throw Error(path + ": damaged checkpoint (its header and its state disagree on the samples per pixel)");
    priorSeconds_ = header.seconds;
}

}  // namespace caustica
