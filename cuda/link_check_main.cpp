// link_check_main.cpp — links the CUDA objects into an executable so CI proves the backend links.
// It does not launch anything (the build machines have no GPU): it only reports what it holds.
#include <cstdio>

#include "caustica/integrators/pass_driver.h"
#include "caustica/parallel/backend.h"
#include "cuda/cuda_backend.h"

int main() {
    // The GPU's instantiations of the single-source drivers (cuda/*_driver.cu).
    auto path = &caustica::makePathPass<caustica::GpuExec>;
    auto direct = &caustica::makeDirectPass<caustica::GpuExec>;
    auto whitted = &caustica::makeWhittedPass<caustica::GpuExec>;
    caustica::registerCudaBackend();  // installs function pointers only; touches no GPU
    const caustica::GpuBackend* backend = caustica::gpuBackend();
    std::printf("caustica GPU drivers linked: path %s, direct %s, whitted %s, primitives backend %s\n",
                path ? "yes" : "no", direct ? "yes" : "no", whitted ? "yes" : "no", backend ? backend->name : "no");
    return backend ? 0 : 1;
}
