// gpu_scene.cu — uploading a Scene and its BVH (see gpu_scene.h).
#include "cuda/gpu_scene.h"

#include <vector>

namespace caustica {
namespace {

/// Uploads `host` into `buffer` and returns the device span (empty for an empty array).
template <class T, class Alloc>
Span<const T> upload(Buffer<T>& buffer, const std::vector<T, Alloc>& host, size_t& bytes) {
    buffer = Buffer<T>(Device::cuda(), host.size());
    if (!host.empty()) buffer.copyFromHost(Span<const T>(host.data(), host.size()));
    bytes += host.size() * sizeof(T);
    return buffer.constSpan();
}

}  // namespace

GpuScene::GpuScene(const Scene& scene, const Bvh& bvh) {
    view_.positions = upload(positions_, scene.positions, bytes_);
    view_.normals = upload(normals_, scene.normals, bytes_);
    view_.uvs = upload(uvs_, scene.uvs, bytes_);
    view_.triangles = upload(triangles_, scene.triangles, bytes_);
    view_.triangleShape = upload(triangleShape_, scene.triangleShape, bytes_);
    view_.spheres = upload(spheres_, scene.spheres, bytes_);
    view_.cylinders = upload(cylinders_, scene.cylinders, bytes_);
    view_.shapes = upload(shapes_, scene.shapes, bytes_);
    view_.bsdfs = upload(bsdfs_, scene.bsdfs, bytes_);
    view_.lights = upload(lights_, scene.lights, bytes_);
    view_.lightCdf = upload(lightCdf_, scene.lightCdf, bytes_);
    view_.lightTexels = upload(lightTexels_, scene.lightTexels, bytes_);  // envmap texels
    view_.environmentLight = scene.environmentLight;
    view_.camera = scene.camera;
    view_.textures = upload(textures_, scene.textures, bytes_);  // BSDF textures and their texels
    view_.texels = upload(texels_, scene.texels, bytes_);
    bvhView_.nodes = upload(nodes_, bvh.nodes, bytes_);
    bvhView_.primIndices = upload(primIndices_, bvh.primIndices, bytes_);
    bvhView_.prims = upload(prims_, bvh.prims, bytes_);
    bvhView_.parents = upload(parents_, bvh.parents, bytes_);  // for the short-stack and stackless traversals
}

}  // namespace caustica
