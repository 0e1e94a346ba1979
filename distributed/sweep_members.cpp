#include "distributed/sweep_members.hpp"

#include <array>
#include <optional>
#include <string>

#include "geometry/error.hpp"

namespace owsim {

Simulation member_simulation(const SweepSpec& spec, std::int64_t member,
                             const SimulationOptions& options) {
  try {
    return Simulation::from_yaml(member_scenario_text(spec, member), spec.base, options);
  } catch (const Error& e) {
    // The member's scenario is the base written anew with the member's values: its line numbers
    // are not the base file's, so "<base>:<line>:" loses the line.
    std::string problem = e.what();
    const std::string base = spec.base.string() + ":";
    const std::size_t after = problem.find_first_not_of("0123456789", base.size());
    if (problem.starts_with(base) && after != std::string::npos && after > base.size() &&
        problem[after] == ':') {
      problem.erase(base.size() - 1, after + 1 - base.size());
    }
    throw Error(spec.file.string() + ": member " + member_folder_name(spec, member) + ": " +
                problem);
  }
}

void check_every_member(Communicator& comm, const SweepSpec& spec,
                        const SimulationOptions& options) {
  std::optional<std::int64_t> failed;
  std::string error;
  for (std::int64_t member = comm.rank(); member < spec.count; member += comm.size()) {
    try {
      static_cast<void>(member_simulation(spec, member, options));
    } catch (const Error& e) {
      failed = member;
      error = e.what();
      break;
    }
  }
  // The maximum of (count − member) over the processes names the lowest failed member.
  std::array<std::uint64_t, 1> lowest = {failed ? static_cast<std::uint64_t>(spec.count - *failed)
                                                : 0};
  comm.max(lowest);
  if (lowest[0] == 0) return;
  if (failed && static_cast<std::uint64_t>(spec.count - *failed) == lowest[0]) {
    throw JobError(error);
  }
  throw ReportedElsewhere();
}

}  // namespace owsim
