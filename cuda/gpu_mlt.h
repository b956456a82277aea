// gpu_mlt.h — many-chain primary-sample-space Metropolis light transport on the GPU (plain C++
// host API; the driver is in gpu_mlt.cu).
//
// The same kernels as the CPU driver (integrators/mlt/mlt_kernel.h, mlt_splat.h), launched as
// CUDA grids by cuda/mlt_kernels.h, with the same host steps (mlt_impl.h): bootstrap on the
// device, b and the chains' starts chosen on the host from the downloaded importances, lock-step
// iterations with the counters reduced on the device, atomic or sort splats, optional Morton
// sorting of the chains. Random streams are the CPU's, so the two drivers sample the same
// distribution; their chains drift apart with rounding (nvcc contracts FMAs), so images agree
// statistically, not bit for bit.
//
// Resumable: save()/load() write and read the CPU driver's checkpoint format
// (integrators/mlt/mlt_checkpoint.h), the chain store transposed to its chain-major layout.
//
// Compact chain state only: the path-tracing kernels are instantiated for CompactChainStore
// alone (each costs minutes of ptxas); --mlt-state float is refused with an Error.
//
// UNVERIFIED: written and compiled for sm_90 on machines without a GPU; it has never run.
#pragma once

#include <cstdint>
#include <memory>

#include "caustica/accel/bvh.h"
#include "caustica/integrators/mlt/mlt_integrator.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// An MltRenderer whose chains live on Device::cuda(): uploads `scene` and `bvh` and allocates
/// the chains' state and scratch. Throws caustica::Error (one line) for invalid settings, for
/// `settings.state == MltStateKind::Float` (before touching the GPU), for a render whose
/// estimated memory (mlt_gpu_memory.h, plus the scene and BVH) exceeds the free device memory
/// (before allocating), and for any CUDA failure (no GPU, out of memory). Needs the CUDA backend registered (registerCudaBackend()).
std::unique_ptr<MltRenderer> makeGpuMltRenderer(const Scene& scene, const Bvh& bvh, const PathSettings& path,
                                                const MltSettings& settings, uint64_t seed);

}  // namespace caustica
