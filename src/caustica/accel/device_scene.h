// device_scene.h — the scene and its ray tracer where a driver's kernels run. On the CPU it is the
// Scene's own arrays and the Accel (Embree or the own BVH); for a GPU the Scene's flat arrays and
// the own BVH are copied to the device once. The views it hands out are the same structs every
// kernel takes (SceneView, BvhView), with spans over the device's memory: pass them by value to
// kernels, never dereference a GPU's on the host.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

#include "caustica/accel/accel.h"
#include "caustica/accel/bvh.h"
#include "caustica/accel/intersector.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/scene/scene.h"

namespace caustica {

class DeviceScene {
public:
    /// On the CPU: views of `scene` and `accel` (nothing copied; both must outlive this). On a
    /// GPU: uploads every flat array of `scene` and of accel's own BVH (synchronous copies; the
    /// Accel must be a Bvh one). Throws caustica::Error on failure (out of memory too).
    DeviceScene(const Scene& scene, const Accel& accel, const Device& device);
    /// Uploads `scene` and `bvh` to `device` (the GPU tests and benchmarks).
    DeviceScene(const Scene& scene, const Bvh& bvh, const Device& device);
    DeviceScene(const DeviceScene&) = delete;
    DeviceScene& operator=(const DeviceScene&) = delete;

    const Device& device() const { return device_; }
    /// Spans over the device's memory, valid while this object lives.
    const SceneView& view() const { return view_; }
    const BvhView& bvhView() const { return bvhView_; }
    BvhIntersector intersector() const { return BvhIntersector{bvhView_, view_}; }
    /// Device bytes held by the uploaded arrays (0 on the CPU, which copies nothing).
    size_t bytes() const { return bytes_; }

    /// f(intersector) with the ray tracer of the CPU's kernels: the Accel's, Embree or the own BVH.
    template <class F>
    decltype(auto) visit(CpuExec, F&& f) const {
        return accel_->visit(std::forward<F>(f));
    }
    /// f(intersector) with the ray tracer of a GPU's kernels: the uploaded own BVH.
    template <class F>
    decltype(auto) visit(GpuExec, F&& f) const {
        return std::forward<F>(f)(intersector());
    }

private:
    void upload(const Scene& scene, const Bvh& bvh);

    Device device_;
    const Accel* accel_ = nullptr;  // the CPU's
    Buffer<Vec3f> positions_, normals_;
    Buffer<Vec2f> uvs_;
    Buffer<Vec3u> triangles_;
    Buffer<uint32_t> triangleShape_;
    Buffer<Sphere> spheres_;
    Buffer<Cylinder> cylinders_;
    Buffer<Shape> shapes_;
    Buffer<Bsdf> bsdfs_;
    Buffer<Light> lights_;
    Buffer<float> lightCdf_;
    Buffer<Spectrum> lightTexels_;
    Buffer<Texture> textures_;
    Buffer<Spectrum> texels_;
    Buffer<BvhNode> nodes_;
    Buffer<uint32_t> primIndices_;
    Buffer<BvhPrimitive> prims_;
    Buffer<uint32_t> parents_;
    Buffer<ParallelogramPlane> quads_;
    SceneView view_;
    BvhView bvhView_;
    size_t bytes_ = 0;
};

}  // namespace caustica
