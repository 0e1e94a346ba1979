// owsim run SCENARIO.yaml — simulate a whole flight (INTERFACE.md): options parsed into the
// facade's SimulationOptions and RunOptions, then owsim::Simulation::run.
#include <fmt/core.h>

#include <string>

#include "cli/commands.hpp"
#include "cli/mpi_job.hpp"
#include "cli/option_checks.hpp"
#include "cli/progress_line.hpp"
#include "distributed/distributed_run.hpp"
#include "owsim/simulation.hpp"

namespace owsim::cli {
namespace {

struct RunCommandOptions {
  std::filesystem::path scenario;
  SimulationOptions simulation;
  RunOptions run;
  std::string outputs;
  bool quiet = false;
};

// The run, in this process alone or as one process of `comm` (quiet except process 0).
void run_flight(RunCommandOptions options, Communicator* comm) {
  RunOptions run = options.run;
  if (!options.outputs.empty()) run.outputs = parse_output_list(options.outputs);
  if (comm != nullptr && options.simulation.threads == 0) {
    options.simulation.threads = default_threads_per_process(*comm);
  }
  const bool speaks = comm == nullptr || comm->rank() == 0;
  const bool quiet = options.quiet || !speaks;
  std::optional<Simulation> opened;
  if (comm == nullptr) {
    opened.emplace(Simulation::open(options.scenario, options.simulation));
  } else {
    std::string error;
    try {
      opened.emplace(Simulation::open(options.scenario, options.simulation));
    } catch (const Error& e) {
      error = e.what();
    }
    throw_if_any_failed(*comm, error);
  }
  const Simulation& simulation = *opened;
  std::optional<ProgressLine> progress;
  if (!quiet) {
    run.progress = [&progress, &simulation](const RunProgress& at) {
      if (!progress) {
        progress.emplace(true, static_cast<std::uint64_t>(at.frames_total),
                         static_cast<std::uint64_t>(at.first_frame));
      }
      progress->frame_done(static_cast<std::uint64_t>(at.frames_done),
                           static_cast<std::uint64_t>(at.frames_done - at.first_frame) *
                               static_cast<std::uint64_t>(simulation.pulses_per_frame()));
    };
  }
  run.notice = [&](std::string_view note) {
    const bool always = note.starts_with("no checkpoint");  // said even with --quiet
    if (speaks && (always || !quiet)) fmt::print(stderr, "owsim run --resume: {}\n", note);
  };
  const RunReport report =
      comm != nullptr ? run_distributed(*comm, simulation, run) : simulation.run(run);
  if (!quiet) {
    fmt::print(stderr,
               "{} frames{}, {} pulses in {:.2f} s ({:.0f} pulses/s, {:.2f}× real time, {}) → {}\n",
               report.frames,
               report.first_frame > 0 ? fmt::format(" (resumed at {})", report.first_frame)
                                      : std::string(),
               report.pulses, report.wall_s, report.pulses_per_s, report.realtime_factor,
               report.processes > 1 || comm != nullptr
                   ? fmt::format("{} processes × {} threads", report.processes, report.threads)
                   : fmt::format("{} threads", report.threads),
               report.directory.string());
  }
}

}  // namespace

void add_run_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<RunCommandOptions>();
  CLI::App* command = app.add_subcommand("run", "simulate a flight: sensor words, points, summary");
  command->add_option("scenario", options->scenario, "scenario file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->run.out, "output folder (default out/<scenario name>/)");
  auto* frames =
      command->add_option("--frames", options->simulation.frames, "number of frames to simulate")
          ->check(positive_number());
  command->add_option("--duration", options->simulation.duration_s, "seconds of flight to simulate")
      ->check(positive_number())
      ->excludes(frames);
  command
      ->add_option("--threads", options->simulation.threads, "worker threads (default: every core)")
      ->check(positive_number());
  command->add_option("--seed", options->simulation.seed, "override the scenario's seed")
      ->check(seed_number());
  command->add_option("--outputs", options->outputs,
                      "comma list of d64, points (or csv, las, ply on their own), trajectory, "
                      "summary, truth, quicklook, mcap (default: all but mcap)");
  command->add_flag("--no-noise", options->simulation.no_noise,
                    "range noise and receiver noise off");
  command->add_flag("--resume", options->run.resume,
                    "continue an interrupted run (same options) from its last complete frame");
  command->add_flag("--quiet", options->quiet, "no progress line");
  command->callback([options] {
    if (started_by_mpi_launcher()) {
      run_in_mpi_job([&](Communicator& comm) { run_flight(*options, &comm); });
    } else {
      run_flight(*options, nullptr);
    }
  });
}

}  // namespace owsim::cli
