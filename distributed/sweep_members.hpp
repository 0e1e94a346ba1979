#pragma once
// The members of a sweep as simulations (distributed/sweep_run.hpp): member m's scenario
// (io/sweep/sweep_file.hpp) opened as its run flies it, and every member opened so before the
// first one flies, so that a bad value in any member refuses the sweep with nothing written.
#include <cstdint>

#include "distributed/communicator.hpp"
#include "io/sweep/sweep_file.hpp"
#include "owsim/simulation.hpp"

namespace owsim {

// Member m's simulation. Errors are one line "<sweep file>: member <name>: <problem>", the
// problem naming the base scenario without a line (the member's text has lines of its own).
[[nodiscard]] Simulation member_simulation(const SweepSpec& spec, std::int64_t member,
                                           const SimulationOptions& options);

// Collective over `comm`: every member's simulation opened and dropped, the members shared out
// over the processes. If any fails, the one with the lowest member number is said: its process
// throws JobError with member_simulation's message, the others ReportedElsewhere.
void check_every_member(Communicator& comm, const SweepSpec& spec,
                        const SimulationOptions& options);

}  // namespace owsim
