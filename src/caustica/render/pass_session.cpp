// pass_session.cpp — the session of the integrators that render by passes of K samples per pixel
// (path, direct, whitted): a driver fills a SamplePass, the Film accumulates it; the checkpoint
// payload is the film's sums.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

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
        : film_(c.scene.film), seed_(c.seed), parameters_(std::move(parameters)), driver_(std::move(driver)),
          samplesPerPass_(samplesPerPass(c)), gpu_(!c.device.isCpu()) {
        description_ = std::string("device: ") + deviceName(c.device.kind) +
                       (gpu_ ? ", " + gpuDescription() + "; gpu-mode " + c.request.gpuMode
                             : "; path-mode " + c.request.pathMode);
        if (!note.empty()) description_ += "\n" + note;
    }

    void step(double samplesLeft) override {
        int k = samplesPerPass_;
        if (samplesLeft > 0) k = std::min(k, int(std::ceil(samplesLeft)));
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
