// aov_pass.cpp — the AOV pass driver for the device this file is compiled for (launch.h: g++
// makes the CPU's; cuda/aov_driver.cu includes this file for nvcc).
#include "caustica/integrators/aov/aov_pass.h"

#include "caustica/accel/device_scene.h"
#include "caustica/integrators/megakernel_pass.h"

namespace caustica {

namespace aov_detail {

/// One work item per slot = pixel * k + s (a named function template: nvcc's rule for kernels).
template <class Exec, class Intersector>
void traceAovPass(Exec exec, const SceneView& view, const Intersector& accel,
                  const AovLayout& layout, uint64_t seed, uint64_t firstSample, int width, int k,
                  size_t slots, Vec2f* positions, float* values) {
    launch(
        exec, "aov.pass", slots,
        [=] CA_HD(size_t slot) {
            const CameraSample c = cameraSample(view.camera, slot / size_t(k), width,
                                                firstSample + slot % size_t(k), seed);
            Hit hit;
            accel.intersect(c.ray, hit);
            positions[slot] = c.pos;
            aovValues(view, c.ray, hit, layout, values + slot * size_t(layout.channels));
        },
        16);
}

}  // namespace aov_detail

template <class Exec>
class AovPass final : public AovPassDriver {
public:
    AovPass(const Scene& scene, const Accel& accel, const AovLayout& layout)
        : scene_(scene, accel, Exec::device()), layout_(layout) {}

    uint64_t render(uint64_t seed, uint64_t firstSampleIndex, AovSamplePass& pass) override {
        const size_t slots = pass.slots();
        if (slots == 0) return 0;
        Vec2f* positions = nullptr;
        float* values = nullptr;
        target_.bind(pass, positions, values);
        scene_.visit(Exec{}, [&](const auto& intersector) {
            aov_detail::traceAovPass(Exec{}, scene_.view(), intersector, layout_, seed,
                                     firstSampleIndex, pass.width, pass.samplesPerPixel, slots,
                                     positions, values);
        });
        target_.copyBack(pass);
        return slots;
    }

private:
    DeviceScene scene_;
    AovLayout layout_;
    AovPassTarget<Exec> target_;
};

template <>
std::unique_ptr<AovPassDriver> makeAovPass<DriverExec>(const Scene& scene, const Accel& accel,
                                                       const AovLayout& layout) {
    return std::make_unique<AovPass<DriverExec>>(scene, accel, layout);
}

}  // namespace caustica
