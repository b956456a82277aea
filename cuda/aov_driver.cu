// aov_driver.cu — the GPU's AOV pass driver: nvcc compiles the same source g++ compiles for the
// CPU (parallel/launch.h makes DriverExec = GpuExec here). Nothing but the include: the driver's
// logic lives once, in src/caustica/integrators/. One .cu per driver, so they compile in parallel.
#include "caustica/integrators/aov/aov_pass.cpp"
