// mpi_runtime.h — MPI for one process of a distributed render (built only when CMake finds MPI):
// initialises MPI for its lifetime and offers MPI_COMM_WORLD as a caustica Communicator
// (distributed/communicator.h). Only the thread that constructed it may call the collectives
// (MPI_THREAD_FUNNELED): the render loop does; TBB's workers never touch MPI.
//
//     MpiRuntime mpi(argc, argv);
//     Renderer r(scene, request, nullptr, mpi.world());
#pragma once

#include <memory>

#include "caustica/distributed/communicator.h"

namespace caustica {

class MpiRuntime {
public:
    /// MPI_Init_thread; throws caustica::Error when MPI cannot start.
    MpiRuntime(int& argc, char**& argv);
    /// MPI_Finalize.
    ~MpiRuntime();
    MpiRuntime(const MpiRuntime&) = delete;
    MpiRuntime& operator=(const MpiRuntime&) = delete;

    Communicator& world() { return *world_; }

    /// Ends every rank of the job with `code` (MPI_Abort): the way out when this rank fails where
    /// the others cannot learn it (in the middle of a collective) and would otherwise wait forever.
    [[noreturn]] static void abortAll(int code);

private:
    std::unique_ptr<Communicator> world_;
};

}  // namespace caustica
