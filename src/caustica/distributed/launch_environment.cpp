#include "caustica/distributed/launch_environment.h"

#include <algorithm>
#include <cstdlib>

namespace caustica {
namespace {

/// The first of `names` set to a non-negative integer, or -1.
template <size_t N>
int firstInteger(const char* const (&names)[N]) {
    for (const char* name : names) {
        const char* text = std::getenv(name);
        if (!text || !*text) continue;
        char* end = nullptr;
        const long v = std::strtol(text, &end, 10);
        if (*end == '\0' && v >= 0 && v < (1L << 30)) return int(v);
    }
    return -1;
}

}  // namespace

bool launchedByMpi() {
    static const char* const names[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"};
    return firstInteger(names) >= 0;
}

int launchedProcessCount() {
    static const char* const names[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"};
    return std::max(firstInteger(names), 1);
}

int localRankFromEnvironment() {
    static const char* const names[] = {"OMPI_COMM_WORLD_LOCAL_RANK", "SLURM_LOCALID", "MPI_LOCALRANKID",
                                        "PMI_LOCAL_RANK"};
    return firstInteger(names);
}

}  // namespace caustica
