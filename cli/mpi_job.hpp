#pragma once
// A command's work as one process of the job mpirun started (distributed/communicator.hpp).
#include <functional>

#include "distributed/communicator.hpp"

namespace owsim::cli {

// Runs `work` with the job's communicator: MPI started before and finalised after. An error every
// process met (JobError) is said once, by process 0, and every process exits non-zero
// (ReportedElsewhere, after the line is written and before MPI is finalised, so the launcher
// cannot tear the job down first); an error one process met alone is said by it, prefixed with its
// rank, and ends the whole job, since the others would wait for it forever.
void run_in_mpi_job(const std::function<void(Communicator&)>& work);

}  // namespace owsim::cli
