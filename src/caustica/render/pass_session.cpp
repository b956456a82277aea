// pass_session.cpp — the session of the integrators that render by passes of K samples per pixel
// (path, direct, whitted): a driver fills a SamplePass, the Film accumulates it; the checkpoint
// payload is the film's sums.
//
// Over N ranks (distributed/communicator.h) a step is N consecutive passes of the single-process
// render: rank r renders pass r (the same sample indices, hence the same random numbers) and
// filters it into per-pixel sums (Film::passSums, the floats addPass would add); the ranks
// all-gather the sums and every rank adds all N to its film in pass order, as one process would
// have added them one step after another. The film is thus the same bits on every rank and the
// image of N ranks byte-identical to one process's at the same spp; a checkpoint of any rank is
// the whole render's. Cost: 16 bytes per pixel per pass, sent by the pass's rank to each other.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "caustica/distributed/agreed_error.h"
#include "caustica/film/film.h"
#include "caustica/integrators/direct/direct_settings.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/parallel/backend.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

/// Samples per pixel of a pass: the request's, or about 256k samples.
int samplesPerPass(const SessionContext& c) {
    const int pixels = c.scene.film.width * c.scene.film.height;
    return c.request.samplesPerPass > 0 ? c.request.samplesPerPass : std::clamp((1 << 18) / std::max(pixels, 1), 1, 16);
}

/// A driver for `c.device` made by `make(exec)`; on a GPU the render's memory estimate is checked
/// first (a one-line Error when it does not fit) and becomes `note`.
template <class Make>
std::unique_ptr<PassDriver> passDriver(const SessionContext& c, PathMode mode, std::string& note, Make&& make) {
    if (!c.device.isCpu()) {
        if (!c.accel.bvh()) throw Error("a GPU traces rays with caustica's own BVH, not Embree");
        note = checkGpuPathMemory(c.scene, *c.accel.bvh(), samplesPerPass(c), mode);
        resetGpuPeakBytes();
    }
    return onDevice(c.device, std::forward<Make>(make));
}

class PassSession final : public IntegratorSession {
public:
    PassSession(const SessionContext& c, std::unique_ptr<PassDriver> driver, RenderIdentity parameters,
                const std::string& note)
        : comm_(c.comm), film_(c.scene.film), seed_(c.seed), parameters_(std::move(parameters)), driver_(std::move(driver)),
          samplesPerPass_(samplesPerPass(c)), gpu_(!c.device.isCpu()) {
        description_ = std::string("device: ") + deviceName(c.device.kind) +
                       (gpu_ ? ", " + gpuDescription() + "; gpu-mode " + c.request.gpuMode
                             : "; path-mode " + c.request.pathMode);
        if (!note.empty()) description_ += "\n" + note;
    }

    void step(double samplesLeft) override {
        if (comm_.size() > 1) return stepOverRanks(samplesLeft);
        const int k = passSamples(samplesLeft);
        if (k != pass_.samplesPerPixel) pass_ = SamplePass(film_.width(), film_.height(), k);
        if (aovChannels_ > 0 && k != aovPass_.samplesPerPixel)
            aovPass_ = AovSamplePass(film_.width(), film_.height(), k, aovChannels_);  // the driver holds &aovPass_
        counters_.rays += driver_->render(seed_, int(film_.samplesPerPixel()), pass_);
        film_.addPass(pass_);
        counters_.samples += uint64_t(film_.width()) * uint64_t(film_.height()) * uint64_t(k);
    }
    double samplesPerPixel() const override { return double(film_.samplesPerPixel()); }
    bool hasImage() const override { return film_.samplesPerPixel() > 0; }
    Image develop() const override { return film_.develop(); }
    SessionCounters counters() const override {
        SessionCounters c = counters_;
        c.invalidSamples = film_.invalidSamples();
        return c;
    }
    RenderIdentity parameters() const override { return parameters_; }
    void save(std::ostream& out) const override { film_.save(out); }
    void load(std::istream& in) override { film_.load(in); }
    std::string description() const override { return description_; }
    bool rendersPixelPasses() const override { return true; }
    const SamplePass* lastPass() const override { return &pass_; }
    std::vector<std::pair<std::string, std::string>> statsJson() const override {
        if (comm_.size() == 1) return {};
        // This rank's bytes (the root writes the statistics): its passes' sums to every other rank.
        return {{"bytes_sent", std::to_string(comm_.bytesSent())},
                {"bytes_sent_per_iteration", std::to_string(steps_ ? comm_.bytesSent() / steps_ : 0)}};
    }
    bool shareFirstHits(const AovLayout& layout) override {
        if (!driver_->shareFirstHits(layout, &aovPass_)) return false;
        aovChannels_ = layout.channels;
        return true;
    }
    const AovSamplePass* lastAovPass() const override { return aovChannels_ > 0 ? &aovPass_ : nullptr; }
    void printSummary(std::FILE* out) const override {
        if (gpu_) std::fprintf(out, "GPU memory  peak %s allocated\n", formatBytes(gpuPeakBytes()).c_str());
    }

private:
    /// Samples per pixel of the next pass with `samplesLeft` to go (<= 0: no sample budget).
    int passSamples(double samplesLeft) const {
        return samplesLeft > 0 ? std::min(samplesPerPass_, int(std::ceil(samplesLeft))) : samplesPerPass_;
    }

    /// One step over the ranks: see the file comment. A rank whose pass fails sends its message
    /// instead of its sums, and every rank then throws it (AgreedError): no rank waits alone.
    void stepOverRanks(double samplesLeft) {
        static_assert(std::is_trivially_copyable_v<PassPixelSums>);
        const int ranks = comm_.size(), me = comm_.rank();
        std::vector<int> k(size_t(ranks), 0), first(size_t(ranks), 0);  // the N passes of this step
        const int spp0 = int(film_.samplesPerPixel());
        int spp = spp0;
        for (int r = 0; r < ranks; ++r) {
            const double left = samplesLeft > 0 ? samplesLeft - double(spp - spp0) : 0;
            if (samplesLeft > 0 && left <= 0) break;
            k[size_t(r)] = passSamples(left);
            first[size_t(r)] = spp;
            spp += k[size_t(r)];
        }
        // [0] = 0: the pass's invalid-sample count (8 bytes) and per-pixel sums follow; 1: an error
        // message follows.
        std::vector<uint8_t> message(1, 0);
        try {
            if (k[size_t(me)] > 0) {
                if (k[size_t(me)] != pass_.samplesPerPixel) pass_ = SamplePass(film_.width(), film_.height(), k[size_t(me)]);
                counters_.rays += driver_->render(seed_, first[size_t(me)], pass_);
                counters_.samples += uint64_t(film_.width()) * uint64_t(film_.height()) * uint64_t(k[size_t(me)]);
                uint64_t invalid = 0;
                const std::vector<PassPixelSums> sums = film_.passSums(pass_, invalid);
                const auto* bytes = reinterpret_cast<const uint8_t*>(sums.data());
                message.resize(1 + sizeof invalid);
                std::memcpy(message.data() + 1, &invalid, sizeof invalid);
                message.insert(message.end(), bytes, bytes + sums.size() * sizeof(PassPixelSums));
            }
        } catch (const std::exception& e) {
            const std::string text = failureMessage(e);
            message.assign(1, 1);
            message.insert(message.end(), text.begin(), text.end());
        }
        const std::vector<std::vector<uint8_t>> passes = comm_.allGather(message);
        for (int r = 0; r < ranks; ++r)
            if (passes[size_t(r)].empty() || passes[size_t(r)][0] != 0)
                throw AgreedError("rank " + std::to_string(r) + ": " +
                                  (passes[size_t(r)].empty() ? std::string("no pass")
                                                             : std::string(passes[size_t(r)].begin() + 1,
                                                                           passes[size_t(r)].end())));
        // Every rank adds the N passes in pass order, as one process adds them step after step.
        std::vector<PassPixelSums> sums(size_t(film_.width()) * size_t(film_.height()));
        for (int r = 0; r < ranks && k[size_t(r)] > 0; ++r) {
            const std::vector<uint8_t>& bytes = passes[size_t(r)];
            uint64_t invalid = 0;
            if (bytes.size() != 1 + sizeof invalid + sums.size() * sizeof(PassPixelSums))
                throw AgreedError("rank " + std::to_string(r) + " sent the sums of another film size");
            std::memcpy(&invalid, bytes.data() + 1, sizeof invalid);
            std::memcpy(sums.data(), bytes.data() + 1 + sizeof invalid, sums.size() * sizeof(PassPixelSums));
            film_.addPassSums(sums, k[size_t(r)], invalid);
        }
        ++steps_;
    }

    Communicator& comm_;
    uint64_t steps_ = 0;  // steps over the ranks in this run
    Film film_;
    uint64_t seed_;
    RenderIdentity parameters_;
    std::unique_ptr<PassDriver> driver_;
    int samplesPerPass_ = 1;
    bool gpu_ = false;
    SamplePass pass_;
    int aovChannels_ = 0;    // > 0: the driver writes the AOVs of its camera rays into aovPass_
    AovSamplePass aovPass_;
    SessionCounters counters_;
    std::string description_;
};

std::string flag(bool b) { return b ? "true" : "false"; }

RenderIdentity pathIdentity(const PathSettings& s) {
    return {identityEntry("max_depth", std::to_string(s.maxDepth)), identityEntry("rr_depth", std::to_string(s.rrDepth)),
            identityEntry("hide_emitters", flag(s.hideEmitters))};
}

RenderIdentity directIdentity(const DirectSettings& s) {
    return {identityEntry("emitter_samples", std::to_string(s.emitterSamples)),
            identityEntry("bsdf_samples", std::to_string(s.bsdfSamples)),
            identityEntry("hide_emitters", flag(s.hideEmitters))};
}

std::string describe(const RenderIdentity& identity) {
    std::string line;
    for (const IdentityEntry& e : identity) line += (line.empty() ? "" : ", ") + e.name + " " + e.value;
    return line;
}

}  // namespace

std::unique_ptr<IntegratorSession> makePathSession(const SessionContext& c) {
    const PathSettings s = readPathSettings(c.params);
    // A GPU runs the path tracer in --gpu-mode, the CPU in --path-mode.
    const PathMode mode = parsePathMode(c.device.isCpu() ? c.request.pathMode : c.request.gpuMode);
    std::string note;
    auto driver = passDriver(c, mode, note, [&](auto exec) {
        return makePathPass<decltype(exec)>(c.scene, c.accel, s, mode);
    });
    return std::make_unique<PassSession>(c, std::move(driver), pathIdentity(s), note);
}

std::unique_ptr<IntegratorSession> makeDirectSession(const SessionContext& c) {
    const DirectSettings s = readDirectSettings(c.params);
    std::string note;
    auto driver = passDriver(c, PathMode::Megakernel, note,
                             [&](auto exec) { return makeDirectPass<decltype(exec)>(c.scene, c.accel, s); });
    return std::make_unique<PassSession>(c, std::move(driver), directIdentity(s), note);
}

std::unique_ptr<IntegratorSession> makeWhittedSession(const SessionContext& c) {
    const WhittedSettings s = readPathSettings(c.params);  // the path tracer's parameters
    std::string note;
    auto driver = passDriver(c, PathMode::Megakernel, note,
                             [&](auto exec) { return makeWhittedPass<decltype(exec)>(c.scene, c.accel, s); });
    return std::make_unique<PassSession>(c, std::move(driver), pathIdentity(s), note);
}

std::string describePath(IntegratorParams& params) { return describe(pathIdentity(readPathSettings(params))); }
std::string describeDirect(IntegratorParams& params) { return describe(directIdentity(readDirectSettings(params))); }

}  // namespace caustica
