// whitted_driver.cu — the GPU's Whitted driver: nvcc compiles the same source g++ compiles for
// the CPU (parallel/launch.h makes DriverExec = GpuExec here). Nothing but the include: the
// driver's logic lives once, in src/caustica/integrators/whitted/.
#include "caustica/integrators/whitted/whitted_pass.cpp"
