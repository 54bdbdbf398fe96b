// One process: the command-line tool built without MPI, and the Python module (a host
// process must not start MPI behind its user's back).
#include "picture_common.hpp"

namespace bouncer::cli {

Ranks mpi_ranks() { return {}; }
void mpi_barrier() {}

}  // namespace bouncer::cli
