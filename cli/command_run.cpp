// owsim run SCENARIO.yaml — simulate a whole flight (INTERFACE.md).
#include <fmt/core.h>

#include <string>

#include "cli/commands.hpp"
#include "cli/flight_run.hpp"
#include "cli/option_checks.hpp"

namespace owsim::cli {

void add_run_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<RunOptions>();
  auto outputs = std::make_shared<std::string>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand("run", "simulate a flight: sensor words, points, summary");
  command->add_option("scenario", options->scenario, "scenario file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "output folder (default out/<scenario name>/)");
  auto* frames = command->add_option("--frames", options->frames, "number of frames to simulate")
                     ->check(positive_number());
  command->add_option("--duration", options->duration_s, "seconds of flight to simulate")
      ->check(positive_number())
      ->excludes(frames);
  command->add_option("--threads", options->threads, "worker threads (default: every core)")
      ->check(positive_number());
  command->add_option("--seed", options->seed, "override the scenario's seed");
  command->add_option("--outputs", *outputs,
                      "comma list of d64, points, trajectory, summary, quicklook (default: all)");
  command->add_flag("--no-noise", options->no_noise, "range noise off (σ = 0)");
  command->add_flag("--resume", options->resume,
                    "continue an interrupted run (same options) from its last complete frame");
  command->add_flag("--quiet", *quiet, "no progress line");
  command->callback([options, outputs, quiet] {
    if (!outputs->empty()) options->outputs = parse_output_list(*outputs);
    options->progress = !*quiet;
    const RunReport report = run_flight_scenario(*options);
    if (!*quiet) {
      fmt::print(stderr,
                 "{} frames{}, {} pulses in {:.2f} s ({:.0f} pulses/s, {:.2f}× real time, {} "
                 "threads) → {}\n",
                 report.frames,
                 report.first_frame > 0 ? fmt::format(" (resumed at {})", report.first_frame)
                                        : std::string(),
                 report.pulses, report.wall_s, report.pulses_per_s, report.realtime_factor,
                 report.threads, report.directory.string());
    }
  });
}

}  // namespace owsim::cli
