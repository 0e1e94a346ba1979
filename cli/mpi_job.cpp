#include "cli/mpi_job.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>

namespace owsim::cli {

namespace {

// This process's rank as the launcher's environment gives it, before MPI is up (0 if unknown).
int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
    if (const char* value = std::getenv(name)) return std::atoi(value);
  }
  return 0;
}

}  // namespace

void run_in_mpi_job(const std::function<void(Communicator&)>& work) {
  std::unique_ptr<Communicator> comm;
  try {
    comm = mpi_communicator();
  } catch (const Error&) {
    // Every process meets it (no module, no MPI): the first says it.
    if (launcher_rank() != 0) throw ReportedElsewhere();
    throw;
  }
  try {
    work(*comm);
  } catch (const JobError&) {
    comm.reset();  // every process ends the job together
    throw;
  } catch (const ReportedElsewhere&) {
    comm.reset();
    throw;
  } catch (const std::exception& e) {
    if (comm->size() == 1) {
      comm.reset();
      throw;
    }
    fmt::print(stderr, "owsim: process {} of {}: {}\n", comm->rank(), comm->size(), e.what());
    std::fflush(stderr);
    comm->abort(1);
  }
}

}  // namespace owsim::cli
