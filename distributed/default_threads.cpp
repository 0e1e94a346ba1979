#include <tbb/info.h>

#include <algorithm>
#include <thread>

#include "distributed/communicator.hpp"

namespace owsim {

int default_threads_per_process(const Communicator& comm) {
  // The cores this process may run on (its affinity mask: mpirun binds processes to cores unless
  // told --bind-to none), and no more than its share of the machine's.
  const auto cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, std::min(tbb::info::default_concurrency(), cores / comm.local_size()));
}

}  // namespace owsim
