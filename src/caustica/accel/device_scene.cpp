// device_scene.cpp — the scene where a driver's kernels run (see device_scene.h).
#include "caustica/accel/device_scene.h"

#include <vector>

#include "caustica/util/error.h"

namespace caustica {
namespace {

/// Uploads `host` into `buffer` on `device` and returns the device span (empty for an empty array).
template <class T, class Alloc>
Span<const T> uploadArray(const Device& device, Buffer<T>& buffer, const std::vector<T, Alloc>& host, size_t& bytes) {
    buffer = Buffer<T>(device, host.size());
    if (!host.empty()) buffer.copyFromHost(Span<const T>(host.data(), host.size()));
    bytes += host.size() * sizeof(T);
    return buffer.constSpan();
}

}  // namespace

DeviceScene::DeviceScene(const Scene& scene, const Accel& accel, const Device& device)
    : device_(device), accel_(&accel) {
    if (device.isCpu()) {
        view_ = accel.sceneView();
        if (accel.bvh()) bvhView_ = accel.bvh()->view();
        return;
    }
    if (!accel.bvh()) throw Error("a GPU traces rays with caustica's own BVH, not Embree");
    upload(scene, *accel.bvh());
}

DeviceScene::DeviceScene(const Scene& scene, const Bvh& bvh, const Device& device) : device_(device) {
    upload(scene, bvh);
}

void DeviceScene::upload(const Scene& scene, const Bvh& bvh) {
    const Device& d = device_;
    view_.positions = uploadArray(d, positions_, scene.positions, bytes_);
    view_.normals = uploadArray(d, normals_, scene.normals, bytes_);
    view_.uvs = uploadArray(d, uvs_, scene.uvs, bytes_);
    view_.triangles = uploadArray(d, triangles_, scene.triangles, bytes_);
    view_.triangleShape = uploadArray(d, triangleShape_, scene.triangleShape, bytes_);
    view_.spheres = uploadArray(d, spheres_, scene.spheres, bytes_);
    view_.cylinders = uploadArray(d, cylinders_, scene.cylinders, bytes_);
    view_.shapes = uploadArray(d, shapes_, scene.shapes, bytes_);
    view_.bsdfs = uploadArray(d, bsdfs_, scene.bsdfs, bytes_);
    view_.lights = uploadArray(d, lights_, scene.lights, bytes_);
    view_.lightCdf = uploadArray(d, lightCdf_, scene.lightCdf, bytes_);
    view_.lightTexels = uploadArray(d, lightTexels_, scene.lightTexels, bytes_);  // envmap texels
    view_.environmentLight = scene.environmentLight;
    view_.camera = scene.camera;
    view_.textures = uploadArray(d, textures_, scene.textures, bytes_);  // BSDF textures and their texels
    view_.texels = uploadArray(d, texels_, scene.texels, bytes_);
    bvhView_.nodes = uploadArray(d, nodes_, bvh.nodes, bytes_);
    bvhView_.primIndices = uploadArray(d, primIndices_, bvh.primIndices, bytes_);
    bvhView_.prims = uploadArray(d, prims_, bvh.prims, bytes_);
    bvhView_.parents = uploadArray(d, parents_, bvh.parents, bytes_);  // for the short-stack and stackless traversals
    bvhView_.quads = uploadArray(d, quads_, bvh.quads, bytes_);        // rectangles tested as planes
}

}  // namespace caustica
