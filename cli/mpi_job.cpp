#include "cli/mpi_job.hpp"

#include <fmt/core.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

namespace owsim::cli {

namespace {

// This process's rank as the launcher's environment gives it, before MPI is up (0 if unknown).
int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
    if (const char* value = std::getenv(name)) return std::atoi(value);
  }
  return 0;
}

// Says the job's one error line now, in one write, while every process is still in the job: once
// one process exits non-zero the launcher tears the job down, and a line left for main() to print
// after MPI_Finalize may never be written.
void say_for_the_job(const std::exception& error) {
  const std::string line = std::string("owsim: ") + error.what() + "\n";
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace

void run_in_mpi_job(const std::function<void(Communicator&)>& work) {
  std::unique_ptr<Communicator> comm;
  try {
    comm = mpi_communicator();
  } catch (const Error& e) {
    // Every process meets it (no module, no MPI): the first says it; the others, with no MPI to
    // wait for it, give its line a moment to reach the launcher before they exit.
    if (launcher_rank() == 0) {
      say_for_the_job(e);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    throw ReportedElsewhere();
  }
  try {
    work(*comm);
  } catch (const JobError& e) {
    say_for_the_job(e);  // before MPI_Finalize, which lets the other processes exit
    comm.reset();        // every process ends the job together
    throw ReportedElsewhere();
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
