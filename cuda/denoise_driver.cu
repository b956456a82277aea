// denoise_driver.cu — the GPU's NL-means denoiser: nvcc compiles the same driver g++ compiles for
// the CPU (parallel/launch.h makes DriverExec = GpuExec here); render/denoise.cpp picks it with
// onDevice. Nothing but the include.
#include "caustica/film/denoise_nlm_pass.cpp"
