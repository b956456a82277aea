// aov_session.cpp — the AOV pass and films beside an integrator's session.
#include "caustica/render/aov_session.h"

#include <cmath>
#include <istream>
#include <limits>
#include <ostream>

#include "caustica/util/error.h"

namespace caustica {

AovSession::AovSession(const Scene& scene, const Accel& accel, Device device, uint64_t seed,
                       AovSpec spec, IntegratorSession& session,
                       const std::string& integrator)
    : scene_(scene),
      spec_(std::move(spec)),
      seed_(seed),
      pixelPasses_(session.rendersPixelPasses()),
      layout_(aovLayout(spec_)) {
    const int w = scene.film.width, h = scene.film.height;
    if (spec_.has(AovType::Variance)) {
        batchMeans_ = !pixelPasses_;
        if (batchMeans_) {
            if (!session.hasStepEstimates())
                throw Error("the variance AOV needs independent pixel samples or per-step estimates; integrator '" +
                            integrator + "' makes neither, and caustica makes up no estimate for it");
            session.recordStepEstimates();
        }
        variance_.emplace(w, h);
    }
    if (layout_.channels > 0) {
        sharedFirstHits_ = pixelPasses_ && session.shareFirstHits(layout_);
        if (!sharedFirstHits_) {
            if (!device.isCpu() && !accel.bvh())
                throw Error("a GPU traces rays with caustica's own BVH, not Embree");
            driver_ = onDevice(device, [&](auto exec) {
                return makeAovPass<decltype(exec)>(scene, accel, layout_);
            });
        }
        film_.emplace(w, h, Filter::fromDesc(scene.film.filter), layout_.channels);
        film_->setEyeWidth(scene.film.eyeWidth);  // a stereo film: the filter stops at the seam
    }
}

AovSession::~AovSession() = default;

uint64_t AovSession::samplesPerPixel() const {
    return film_ ? film_->samplesPerPixel() : 0;
}

void AovSession::afterStep(const IntegratorSession& session, double samplesBefore) {
    const SamplePass* pass = pixelPasses_ ? session.lastPass() : nullptr;
    if (pixelPasses_ && !pass)
        throw Error("internal: an integrator session that renders passes showed none");
    if (variance_ && pass) variance_->addPass(*pass);
    if (variance_ && batchMeans_)
        if (const Image* estimate = session.lastStepEstimate()) variance_->addEstimate(*estimate);
    if (!film_) return;
    int k = 1;
    uint64_t first = film_->samplesPerPixel();
    if (pass) {
        // Exactly the pass's camera samples: indices samplesBefore .. + K.
        k = pass->samplesPerPixel;
        first = uint64_t(std::llround(samplesBefore));
    } else if (first >= kAovSamplesPerPixelCap) {
        return;
    }
    if (sharedFirstHits_) {
        const AovSamplePass* shared = session.lastAovPass();
        if (!shared || shared->samplesPerPixel != k)
            throw Error("internal: the integrator's pass wrote no AOVs for its samples");
        film_->addPass(*shared);
        return;
    }
    if (pass_.samplesPerPixel != k)
        pass_ = AovSamplePass(film_->width(), film_->height(), k, layout_.channels);
    rays_ += driver_->render(seed_, first, pass_);
    film_->addPass(pass_);
}

AovImage AovSession::develop() const {
    AovImage image;
    image.width = scene_.film.width;
    image.height = scene_.film.height;
    image.spec = spec_;
    image.channels = spec_.channelNames();
    const size_t pixels = size_t(image.width) * size_t(image.height), C = image.channels.size();
    image.values.assign(pixels * C, 0.0f);
    const std::vector<float> geometric = film_ ? film_->develop() : std::vector<float>();
    // Batch means of fewer than 2 batches: NaN, no number (the denoiser then estimates its own).
    const std::vector<float> variance =
        variance_ ? variance_->develop(batchMeans_ ? std::numeric_limits<float>::quiet_NaN() : 0.0f)
                  : std::vector<float>();
    // Interleave the geometric film's channels and the variance's in the spec's order.
    size_t out = 0, in = 0;
    for (const AovLayer& layer : spec_.layers) {
        const int n = aovChannelCount(layer.type);
        for (int c = 0; c < n; ++c, ++out) {
            for (size_t p = 0; p < pixels; ++p)
                image.values[p * C + out] = layer.type == AovType::Variance
                                                ? variance[p * 3 + size_t(c)]
                                                : geometric[p * size_t(layout_.channels) + in];
            if (layer.type != AovType::Variance) ++in;
        }
    }
    return image;
}

void AovSession::save(std::ostream& out) const {
    if (film_) film_->save(out);
    if (variance_) variance_->save(out);
}

void AovSession::load(std::istream& in, double sessionSamplesPerPixel) {
    if (film_) film_->load(in);
    if (variance_) variance_->load(in);
    if (film_ && pixelPasses_ &&
        film_->samplesPerPixel() != uint64_t(std::llround(sessionSamplesPerPixel)))
        throw Error("damaged checkpoint (its AOVs hold " +
                    std::to_string(film_->samplesPerPixel()) + " samples per pixel, the image " +
                    std::to_string(sessionSamplesPerPixel) + ")");
}

}  // namespace caustica
