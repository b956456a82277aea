// launch_environment.h — what the environment says about how this process was started: by an MPI
// launcher (mpirun, mpiexec, srun) or alone, and which rank of its host it is. Read before MPI is
// initialised (a binary built with MPI initialises it only when launched by one) and to pick one
// GPU per rank on a host.
#pragma once

namespace caustica {

/// Whether an MPI launcher started this process: OpenMPI (OMPI_COMM_WORLD_SIZE), PMIx
/// (PMIX_RANK), PMI-1/2 as MPICH and Slurm's srun --mpi set (PMI_SIZE, PMI_RANK).
bool launchedByMpi();

/// The number of processes the launcher started together (OMPI_COMM_WORLD_SIZE, PMI_SIZE, and
/// Slurm's SLURM_STEP_NUM_TASKS for srun), or 1 when none says.
int launchedProcessCount();

/// The rank of this process among the ranks on its host (OMPI_COMM_WORLD_LOCAL_RANK,
/// SLURM_LOCALID, MPI_LOCALRANKID, PMI_LOCAL_RANK), or -1 when no launcher says.
int localRankFromEnvironment();

}  // namespace caustica
