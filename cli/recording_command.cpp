#include "cli/recording_command.hpp"

#include <tbb/info.h>

#include <cstddef>

namespace owsim::cli {
namespace {

std::size_t worker_threads(int requested) {
  return static_cast<std::size_t>(requested > 0 ? requested : tbb::info::default_concurrency());
}

// The scenario with the overrides applied, once the recording's format is checked against it.
Scenario scenario_of(const RecordingCommandOptions& options) {
  Scenario scenario = load_recording_scenario(options.scenario, options.overrides);
  check_recording_format(options.recording, options.format, scenario);
  return scenario;
}

}  // namespace

void add_recording_options(CLI::App& command, RecordingCommandOptions& options,
                           const RecordingOptionHelp& help) {
  command
      .add_option(help.recording_name, options.recording,
                  "a MilOWS (.d64) or HELLAS (.hellas) word file")
      ->required()
      ->check(CLI::ExistingFile);
  command.add_option("--scenario", options.scenario, help.scenario)
      ->required()
      ->check(CLI::ExistingFile);
  command.add_option("--out", options.out, help.out)->required();
  command
      .add_option("--trajectory", options.overrides.trajectory,
                  "navigation file instead of the scenario's trajectory")
      ->check(CLI::ExistingFile);
  command
      .add_option("--trajectory-format", options.overrides.trajectory_format,
                  "hellsim | csv | sbet (default: csv for .csv, else hellsim)")
      ->check(CLI::IsMember({"hellsim", "csv", "sbet"}));
  command.add_option("--format", options.format, "d64 | hellas, when the extension does not say")
      ->check(CLI::IsMember({"d64", "hellas"}));
  command.add_option("--start-s", options.start_s,
                     "approximate time of the first pulse on the trajectory's clock: picks the "
                     "time tags' wrap nearest it (default: the first from trajectory.start_s on)");
  command.add_option("--threads", options.threads, "worker threads (default: every core)")
      ->check(CLI::PositiveNumber);
  command.add_flag("--quiet", options.quiet, "no report on stderr");
}

OpenRecording::OpenRecording(const RecordingCommandOptions& options)
    : parallelism(tbb::global_control::max_allowed_parallelism, worker_threads(options.threads)),
      scenario(scenario_of(options)),
      decoder(options.recording, scenario.scan, {options.start_s}),
      scene(scenario, decoder.layout()),
      progress(!options.quiet, decoder.layout().frames) {}

}  // namespace owsim::cli
