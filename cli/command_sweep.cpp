// owsim sweep SWEEP.yaml — a campaign of runs (INTERFACE.md "Beyond one machine"), alone or as
// one process of an MPI job: distributed/sweep_run.hpp.
#include <fmt/core.h>

#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/mpi_job.hpp"
#include "cli/option_checks.hpp"
#include "distributed/sweep_run.hpp"

namespace owsim::cli {
namespace {

struct SweepCommandOptions {
  std::filesystem::path sweep;
  std::optional<std::filesystem::path> out;
  int threads = 0;
  bool resume = false;
  bool quiet = false;
};

void run_campaign(const SweepCommandOptions& options, Communicator& comm) {
  std::optional<SweepSpec> spec;
  std::string error;
  try {
    spec.emplace(read_sweep_file(options.sweep));
  } catch (const Error& e) {
    error = e.what();
  }
  throw_if_any_failed(comm, error);
  const bool speaks = comm.rank() == 0;
  SweepRunOptions run;
  run.out = options.out ? *options.out : std::filesystem::path("out") / options.sweep.stem();
  run.resume = options.resume;
  run.threads = options.threads;
  if (!options.quiet || options.resume) {
    run.notice = [&](std::string_view note) {
      const bool always = note.starts_with("no sweep state");  // said even with --quiet
      if (always || !options.quiet) {
        fmt::print(stderr, "owsim sweep{}: {}\n",
                   comm.size() > 1 ? fmt::format(" [process {}]", comm.rank()) : std::string(),
                   note);
      }
    };
  }
  const SweepReport report = run_sweep(comm, *spec, run);
  if (speaks && !options.quiet) {
    fmt::print(stderr,
               "{} members ({} run, {} complete before), {} pulses in {:.2f} s ({:.0f} pulses/s, "
               "{} processes × {} threads) → {}\n",
               report.members, report.ran, report.skipped, report.pulses, report.wall_s,
               report.pulses_per_s, report.processes, report.threads,
               (run.out / "sweep.csv").string());
  }
}

}  // namespace

void add_sweep_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<SweepCommandOptions>();
  CLI::App* command =
      app.add_subcommand("sweep", "a campaign: many runs from a base scenario and varied keys");
  command->add_option("sweep", options->sweep, "sweep file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "output folder (default out/<sweep name>/)");
  command
      ->add_option("--threads", options->threads,
                   "worker threads per process (default: its share of the cores)")
      ->check(positive_number());
  command->add_flag("--resume", options->resume,
                    "continue an interrupted sweep: skip complete members, resume the others");
  command->add_flag("--quiet", options->quiet, "no line per member");
  command->callback([options] {
    if (started_by_mpi_launcher()) {
      run_in_mpi_job([&](Communicator& comm) { run_campaign(*options, comm); });
    } else {
      run_campaign(*options, *single_process_communicator());
    }
  });
}

}  // namespace owsim::cli
