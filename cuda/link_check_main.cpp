// link_check_main.cpp — links the CUDA objects into an executable so CI proves the backend links.
// It does not launch anything (the build machines have no GPU): it only reports what it holds.
#include <cstdio>

#include "caustica/parallel/backend.h"
#include "cuda/cuda_backend.h"
#include "kernel_check.h"

int main() {
    auto path = &caustica::launchPathMegakernel;
    auto gather = &caustica::launchFilmSplat;
    caustica::registerCudaBackend();  // installs function pointers only; touches no GPU
    const caustica::GpuBackend* backend = caustica::gpuBackend();
    std::printf(
        "caustica CUDA kernels linked: path megakernel %s, film splat %s, "
        "primitives backend %s\n",
        path ? "yes" : "no", gather ? "yes" : "no", backend ? backend->name : "no");
    return backend ? 0 : 1;
}
