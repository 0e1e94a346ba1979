#include <array>

#include "distributed/communicator.hpp"

namespace owsim {

void throw_if_any_failed(Communicator& comm, const std::string& error) {
  // The maximum of (size − rank) over the failed processes names the lowest-ranked of them.
  std::array<std::uint64_t, 1> failed = {
      error.empty() ? 0 : static_cast<std::uint64_t>(comm.size() - comm.rank())};
  comm.max(failed);
  if (failed[0] == 0) return;
  if (static_cast<int>(static_cast<std::uint64_t>(comm.size()) - failed[0]) == comm.rank()) {
    throw JobError(error);
  }
  throw ReportedElsewhere();
}

}  // namespace owsim
