#include "ranks.h"

#include <cstdio>
#include <string>

#include "caustica/distributed/agreed_error.h"
#include "caustica/distributed/launch_environment.h"
#include "caustica/util/error.h"
#ifdef CAUSTICA_WITH_MPI
#include "caustica/mpi/mpi_runtime.h"
#endif

namespace caustica::cli {

#ifdef CAUSTICA_WITH_MPI
struct Ranks::Mpi {
    MpiRuntime runtime;
    Mpi(int& argc, char**& argv) : runtime(argc, argv) {}
};
#else
struct Ranks::Mpi {};
#endif

Ranks::Ranks(int& argc, char**& argv) {
    const int launched = launchedProcessCount();
#ifdef CAUSTICA_WITH_MPI
    if (launchedByMpi()) {
        mpi_ = std::make_unique<Mpi>(argc, argv);
        if (launched > 1 && mpi_->runtime.world().size() == 1)
            throw Error("the launcher started " + std::to_string(launched) + " processes but MPI sees each alone (" +
                        "srun: pass --mpi=pmix; mpirun: use the MPI caustica was built with)");
        return;
    }
    if (launched > 1)
        throw Error("srun started " + std::to_string(launched) +
                    " processes without an MPI plugin: run srun --mpi=pmix (or mpirun) for one render over them");
#else
    (void)argc;
    (void)argv;
    if (launched > 1)
        throw Error("started as one of " + std::to_string(launched) +
                    " processes, but this caustica was built without MPI: each would render the whole image "
                    "alone (rebuild with libopenmpi-dev installed, docs/MPI.md)");
#endif
}

Ranks::~Ranks() = default;

Communicator& Ranks::comm() {
#ifdef CAUSTICA_WITH_MPI
    if (mpi_) return mpi_->runtime.world();
#endif
    return singleProcess();
}

int Ranks::fail(const std::exception& error) {
    const std::string message = failureMessage(error);
    Communicator& c = comm();
    if (c.size() == 1 || dynamic_cast<const AgreedError*>(&error)) {
        std::fprintf(stderr, "caustica: error: %s\n", message.c_str());
        return 1;
    }
    std::fprintf(stderr, "caustica: error: rank %d: %s\n", c.rank(), message.c_str());
    std::fflush(stderr);
#ifdef CAUSTICA_WITH_MPI
    MpiRuntime::abortAll(1);
#endif
    return 1;
}

}  // namespace caustica::cli
