// MPI ranks for the grid commands (built only when CMake finds MPI: BOUNCER_WITH_MPI).
// Under `mpirun -n K`, rank r runs shard r/K of the tiles into the shared PREFIX.tiles/,
// and rank 0 writes the outputs once every rank is done (see run_job in picture_common.hpp).
// A plain run (no mpirun) never initialises MPI.
#include <mpi.h>

#include <cstdlib>

#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}

void finalize() {
  int done = 0;
  MPI_Finalized(&done);
  if (!done) MPI_Finalize();
}

}  // namespace

Ranks mpi_ranks() {
  static const Ranks world = [] {
    Ranks w;
    if (!launched_by_mpirun()) return w;
    int provided = 0;
    // Only the main thread calls MPI; the grid's worker threads never do.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    std::atexit(finalize);
    MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &w.size);
    return w;
  }();
  return world;
}

void mpi_barrier() {
  if (mpi_ranks().size > 1) MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace bouncer::cli
