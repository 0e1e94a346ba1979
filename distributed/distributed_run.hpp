#pragma once
// `mpirun -np N owsim run` (INTERFACE.md "Beyond one machine"): one flight's frames over the
// processes of a job, every output file byte for byte what one process writes.
//
// The frames go in rounds: in each, process r simulates the r-th block of `frames_per_block`
// consecutive frames after the previous round's (with its own threads) and encodes them. The
// bytes of every output are then placed: each process's byte counts are summed over the
// processes before it (an exclusive scan), which gives its offset after everything written so
// far, and all write at once (MPI-IO collective writes into the `.partial` temporaries, so the
// words, points.csv/.las/.ply go straight to their places). What the frames add besides bytes —
// the summary's counts and ground truth, the trajectory rows, the LAS header's counts and bounds,
// the quick-look map's trajectory, flight.mcap's chunks (one a frame, built and compressed by the
// process that simulated it; a chunk's index entry depends on where it lands, so process 0
// appends them, one round's at a time) — is gathered at process 0, which keeps the files' state
// exactly as FlightOutputs does in one process (add_placed_frame, in frame order), writes the
// checkpoint when one is due (after every process's bytes are synced and the map's hits ORed
// together), and at the end completes the headers, summary.json and map.png and renames the
// files. The checkpoint is the one-process run's: `--resume` continues it with any number of
// processes, and a one-process run can resume a distributed one.
//
// A shared file system is needed where the processes run on several hosts (the output folder the
// same path everywhere). A process that fails alone ends the job (Communicator::abort) after
// saying why; a failure every process meets (a bad checkpoint, an output folder that cannot be
// made) is said once, by process 0, and the others throw ReportedElsewhere.
#include <cstdint>

#include "distributed/communicator.hpp"
#include "owsim/simulation.hpp"

namespace owsim {

struct DistributedRunOptions {
  std::int64_t frames_per_block = 0;  // per process and round; 0: 4 per thread, at least 8
};

// Run on every process of `comm` with the same simulation and options. The report (process 0's;
// the others' hold the same frame counts) counts the pulses of every process.
[[nodiscard]] RunReport run_distributed(Communicator& comm, const Simulation& simulation,
                                        const RunOptions& options,
                                        const DistributedRunOptions& distribution = {});

}  // namespace owsim
