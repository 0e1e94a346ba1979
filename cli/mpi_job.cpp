#include "cli/mpi_job.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <memory>

namespace owsim::cli {

void run_in_mpi_job(const std::function<void(Communicator&)>& work) {
  std::unique_ptr<Communicator> comm = mpi_communicator();
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
