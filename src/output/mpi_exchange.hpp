#pragma once
// The processes of `mpirun -np K sympl ...`: MPI is started only when the
// program was launched by an MPI launcher (its environment says so), so a
// plain `sympl ensemble` never touches MPI.
#include "commands/ensemble_run.hpp"

namespace sympl::app {

// One process (rank 0 of 1) unless launched by mpirun; then the MPI ranks
// (Boost.MPI), or an error when this build has no MPI.
exchange process_exchange();

// Whether this build can run over MPI ranks.
bool built_with_mpi();

}  // namespace sympl::app
