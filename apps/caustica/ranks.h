// ranks.h — the ranks this process renders with: MPI_COMM_WORLD when the binary has MPI and an
// MPI launcher (mpirun, srun --mpi=pmix) started it, else one process alone. MPI lives as long as
// this object (MPI_Init ... MPI_Finalize).
#pragma once

#include <exception>
#include <memory>

#include "caustica/distributed/communicator.h"

namespace caustica::cli {

class Ranks {
public:
    /// Throws caustica::Error when a launcher started several processes that cannot form one
    /// render (a binary without MPI, srun without an MPI plugin).
    Ranks(int& argc, char**& argv);
    ~Ranks();

    Communicator& comm();

    /// The exit of a command that threw `error`: prints "caustica: error: MESSAGE" and returns 1.
    /// Over several ranks, an error not every rank knows (not an AgreedError: a throw in the
    /// middle of a collective) prints "rank R: MESSAGE" and ends every rank (MPI_Abort), since the
    /// others may be waiting for this one.
    int fail(const std::exception& error);

private:
    struct Mpi;
    std::unique_ptr<Mpi> mpi_;
};

}  // namespace caustica::cli
