// link_check_main.cpp — links the CUDA objects into an executable so CI proves the backend links.
// It does not launch anything (the build machines have no GPU): it only reports what it holds.
#include <cstdio>

#include "kernel_check.h"

int main() {
    auto path = &caustica::launchPathMegakernel;
    auto gather = &caustica::launchFilmSplat;
    std::printf("caustica CUDA kernels linked: path megakernel %s, film splat %s\n",
                path ? "yes" : "no", gather ? "yes" : "no");
    return 0;
}
