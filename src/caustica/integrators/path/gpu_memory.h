// gpu_memory.h — what a path-traced render needs in GPU memory, estimated from sizes alone
// before anything is uploaded, so that `caustica render --device cuda` can refuse a render that
// does not fit instead of failing halfway. Plain C++: the CPU build and tests use it too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace caustica {

struct Scene;
struct Bvh;

enum class PathMode { Megakernel, Wavefront };

/// "megakernel" / "wavefront"; parsePathMode throws caustica::Error on anything else.
PathMode parsePathMode(const std::string& name);
const char* pathModeName(PathMode mode);

/// Element counts of everything a GPU render holds: the scene's flat arrays, the own BVH and the
/// pass dimensions. A pure description (no pointers), filled by gpuRenderSizes or by hand.
struct GpuRenderSizes {
    size_t positions = 0, normals = 0, uvs = 0, triangles = 0, triangleShape = 0, spheres = 0,
           cylinders = 0, shapes = 0, bsdfs = 0, lights = 0, lightCdf = 0, lightTexels = 0,
           textures = 0, texels = 0;
    size_t bvhNodes = 0, bvhPrimIndices = 0, bvhPrims = 0, bvhParents = 0, bvhQuads = 0;
    int width = 0, height = 0;
    int samplesPerPass = 1;                 // K: samples per pixel in one pass
    PathMode mode = PathMode::Megakernel;
    size_t maxPathsInFlight = size_t(1) << 20;  // wavefront: paths traced at once
};

/// Bytes, by use. `scratch` is the primitives' temporary storage (CUB compaction in the
/// wavefront), bounded generously; `total()` is what must fit in free device memory.
struct GpuMemoryEstimate {
    size_t scene = 0;       // scene arrays
    size_t bvh = 0;         // BVH nodes, leaf-order primitive ids and records, parent links
    size_t pathState = 0;   // per path in flight: wavefront state, megakernel ray counters
    size_t samplePass = 0;  // one pass of PixelSamples (W * H * K)
    size_t scratch = 0;
    size_t pathsInFlight = 0;
    size_t total() const { return scene + bvh + pathState + samplePass + scratch; }
};

/// Bytes of per-path state the wavefront keeps in flight on any device: PathState, sampler, hit,
/// shadow ray, three queues, two flag arrays and the compaction output.
size_t wavefrontBytesPerPath();

/// The estimate for `sizes`: a pure function (no GPU needed), tested on the CPU.
GpuMemoryEstimate estimateGpuMemory(const GpuRenderSizes& sizes);

/// The sizes of rendering `scene` with `bvh` at the film's resolution, K samples per pass.
GpuRenderSizes gpuRenderSizes(const Scene& scene, const Bvh& bvh, int samplesPerPass,
                              PathMode mode, size_t maxPathsInFlight = size_t(1) << 20);

/// For a path-traced render on a GPU, before anything is uploaded: the estimate as a line for the
/// start of the render ("GPU memory needed: about ..."); throws caustica::Error (one line naming
/// what to lower) when it exceeds the GPU's free memory. Without a GPU to ask, the line says so and
/// the first allocation reports the error.
std::string checkGpuPathMemory(const Scene& scene, const Bvh& bvh, int samplesPerPass, PathMode mode);

/// "1.50 GiB" / "12.3 MiB" / "512 B".
std::string formatBytes(size_t bytes);

}  // namespace caustica
