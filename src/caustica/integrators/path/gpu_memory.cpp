#include "caustica/integrators/path/gpu_memory.h"

#include <algorithm>
#include <cstdio>

#include "caustica/accel/bvh.h"
#include "caustica/film/film.h"
#include "caustica/parallel/backend.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"

namespace caustica {

PathMode parsePathMode(const std::string& name) {
    if (name == "megakernel") return PathMode::Megakernel;
    if (name == "wavefront") return PathMode::Wavefront;
    throw Error("unknown GPU path mode '" + name + "' (expected megakernel or wavefront)");
}

const char* pathModeName(PathMode mode) {
    return mode == PathMode::Wavefront ? "wavefront" : "megakernel";
}

size_t wavefrontBytesPerPath() {
    return sizeof(PathState) + sizeof(IndependentSampler) + sizeof(Hit) + sizeof(ShadowRay) +
           6 * sizeof(uint32_t);
}

GpuMemoryEstimate estimateGpuMemory(const GpuRenderSizes& s) {
    GpuMemoryEstimate e;
    e.scene = s.positions * sizeof(Vec3f) + s.normals * sizeof(Vec3f) + s.uvs * sizeof(Vec2f) +
              s.triangles * sizeof(Vec3u) + s.triangleShape * sizeof(uint32_t) +
              s.spheres * sizeof(Sphere) + s.shapes * sizeof(Shape) + s.bsdfs * sizeof(Bsdf) +
              s.lights * sizeof(Light) + s.lightCdf * sizeof(float) + s.cylinders * sizeof(Cylinder) +
              s.lightTexels * sizeof(Spectrum) + s.textures * sizeof(Texture) + s.texels * sizeof(Spectrum);
    e.bvh = s.bvhNodes * sizeof(BvhNode) + s.bvhPrimIndices * sizeof(uint32_t) +
            s.bvhPrims * sizeof(BvhPrimitive) + s.bvhParents * sizeof(uint32_t) +
            s.bvhQuads * sizeof(ParallelogramPlane);
    const size_t samples = size_t(std::max(s.width, 0)) * size_t(std::max(s.height, 0)) *
                           size_t(std::max(s.samplesPerPass, 0));
    e.samplePass = samples * sizeof(PixelSample);
    if (s.mode == PathMode::Wavefront) {
        e.pathsInFlight = std::min(samples, std::max<size_t>(s.maxPathsInFlight, 1));
        e.pathState = e.pathsInFlight * wavefrontBytesPerPath();
        // CUB's DeviceSelect temporaries are far below one word per element; plus its counter.
        e.scratch = e.pathsInFlight * sizeof(uint32_t) + (size_t(1) << 20);
    } else {
        e.pathsInFlight = samples;                    // one thread per (pixel, sample)
        e.pathState = samples * sizeof(uint32_t);     // per-sample ray counters
        e.scratch = 0;
    }
    return e;
}

GpuRenderSizes gpuRenderSizes(const Scene& scene, const Bvh& bvh, int samplesPerPass,
                              PathMode mode, size_t maxPathsInFlight) {
    GpuRenderSizes s;
    s.positions = scene.positions.size();
    s.normals = scene.normals.size();
    s.uvs = scene.uvs.size();
    s.triangles = scene.triangles.size();
    s.triangleShape = scene.triangleShape.size();
    s.spheres = scene.spheres.size();
    s.shapes = scene.shapes.size();
    s.bsdfs = scene.bsdfs.size();
    s.lights = scene.lights.size();
    s.lightCdf = scene.lightCdf.size();
    s.cylinders = scene.cylinders.size();
    s.lightTexels = scene.lightTexels.size();
    s.textures = scene.textures.size();
    s.texels = scene.texels.size();
    s.bvhNodes = bvh.nodes.size();
    s.bvhPrimIndices = bvh.primIndices.size();
    s.bvhPrims = bvh.prims.size();
    s.bvhParents = bvh.parents.size();  // uploaded for the short-stack and stackless traversals
    s.bvhQuads = bvh.quads.size();
    s.width = scene.film.width;
    s.height = scene.film.height;
    s.samplesPerPass = samplesPerPass;
    s.mode = mode;
    s.maxPathsInFlight = maxPathsInFlight;
    return s;
}

std::string checkGpuPathMemory(const Scene& scene, const Bvh& bvh, int samplesPerPass, PathMode mode) {
    const GpuMemoryEstimate need = estimateGpuMemory(gpuRenderSizes(scene, bvh, samplesPerPass, mode));
    size_t freeBytes = 0, totalBytes = 0;
    const bool known = gpuMemoryInfo(freeBytes, totalBytes);
    if (known && need.total() > freeBytes)
        throw Error("GPU memory: the render needs about " + formatBytes(need.total()) + " but only " +
                    formatBytes(freeBytes) + " is free on " + gpuDescription() +
                    "; lower --res or --spp-per-pass, or use --device cpu");
    return "GPU memory needed: about " + formatBytes(need.total()) + " (scene " + formatBytes(need.scene) +
           ", BVH " + formatBytes(need.bvh) + ", path state " + formatBytes(need.pathState) + " for " +
           std::to_string(need.pathsInFlight) + " paths, sample pass " + formatBytes(need.samplePass) +
           ", scratch " + formatBytes(need.scratch) + "); " +
           (known ? "free " + formatBytes(freeBytes) + " of " + formatBytes(totalBytes) : "free memory unknown");
}

std::string formatBytes(size_t bytes) {
    char text[32];
    const double b = double(bytes);
    if (b >= double(size_t(1) << 30))
        std::snprintf(text, sizeof text, "%.2f GiB", b / double(size_t(1) << 30));
    else if (b >= double(size_t(1) << 20))
        std::snprintf(text, sizeof text, "%.1f MiB", b / double(size_t(1) << 20));
    else if (b >= 1024.0)
        std::snprintf(text, sizeof text, "%.1f KiB", b / 1024.0);
    else
        std::snprintf(text, sizeof text, "%zu B", bytes);
    return text;
}

}  // namespace caustica
