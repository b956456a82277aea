// gpu_scene.h — a Scene and its own BVH copied to the GPU once (plain C++: includable without
// nvcc). The views it hands out are the same structs the CPU kernels take (SceneView, BvhView),
// with spans over device memory: pass them by value to kernels, never dereference them on the
// host.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/accel/bvh.h"
#include "caustica/accel/intersector.h"
#include "caustica/parallel/buffer.h"
#include "caustica/scene/scene.h"

namespace caustica {

class GpuScene {
public:
    /// Uploads every flat array of `scene` and of `bvh` to Device::cuda() (synchronous copies).
    /// Needs the CUDA backend registered; throws caustica::Error on failure (out of memory too).
    GpuScene(const Scene& scene, const Bvh& bvh);
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    /// Spans over device memory, valid while this object lives.
    const SceneView& view() const { return view_; }
    const BvhView& bvhView() const { return bvhView_; }
    BvhIntersector intersector() const { return BvhIntersector{bvhView_, view_}; }
    /// Device bytes held by the uploaded arrays.
    size_t bytes() const { return bytes_; }

private:
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
    SceneView view_;
    BvhView bvhView_;
    size_t bytes_ = 0;
};

}  // namespace caustica
