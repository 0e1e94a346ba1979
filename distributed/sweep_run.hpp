#pragma once
// `owsim sweep SWEEP.yaml --out DIR [--resume]` (INTERFACE.md "Beyond one machine"): every member
// of the sweep file (io/sweep/sweep_file.hpp) a full `owsim run` into DIR/<member>/, handed out
// to the processes of the job as they become free (distributed/member_dispenser.hpp), each member
// on all of its process's threads; then DIR/sweep.csv (io/sweep/sweep_table.hpp). One process
// without MPI runs the members one after another on every core.
//
// DIR/.owsim-sweep.json names the sweep (owsim version, sweep file and base scenario contents):
// `--resume` refuses a folder of another sweep, skips members whose summary.json is there (a
// member's summary.json is the last file its run completes) and resumes the others from their own
// checkpoints (`owsim run --resume`), so an interrupted sweep finishes with the bytes of an
// uninterrupted one.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string_view>

#include "distributed/communicator.hpp"
#include "io/sweep/sweep_file.hpp"

namespace owsim {

struct SweepRunOptions {
  std::filesystem::path out;
  bool resume = false;
  int threads = 0;  // per process; 0: default_threads_per_process
  // After each member this process ran or skipped: "member 0007 done (…)".
  std::function<void(std::string_view)> notice;
};

struct SweepReport {
  std::int64_t members = 0;
  std::int64_t ran = 0;             // by every process, this time
  std::int64_t skipped = 0;         // complete before (--resume)
  std::uint64_t pulses = 0;         // simulated this time, by every process
  double wall_s = 0.0;              // process 0's, from the first member to sweep.csv
  double pulses_per_s = 0.0;        // aggregate
  int processes = 1;
  int threads = 1;                  // per process
};

// Collective over `comm`. Errors met by every process (a bad folder state) throw JobError at
// process 0 and ReportedElsewhere elsewhere; a member that fails throws from the process running
// it.
[[nodiscard]] SweepReport run_sweep(Communicator& comm, const SweepSpec& spec,
                                    const SweepRunOptions& options);

}  // namespace owsim
