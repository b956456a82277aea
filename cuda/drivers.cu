// drivers.cu — the GPU's drivers: nvcc compiles the same driver sources g++ compiles for the CPU
// (launch.h makes DriverExec = GpuExec here). Nothing but includes: a driver's logic lives once,
// in src/caustica/integrators/.
#include "caustica/integrators/direct/direct_pass.cpp"
#include "caustica/integrators/mlt/mlt_driver.cpp"
#include "caustica/integrators/path/path_pass.cpp"
#include "caustica/integrators/sppm/sppm_driver.cpp"
