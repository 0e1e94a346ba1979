// owsim merge RECORDING --scenario S [--trajectory T] --out FILE — put a scenario's objects into a
// recording (INTERFACE.md; SENSOR-SPEC §9; io/recording/recording_merge.hpp).
#include <fmt/core.h>

#include <cstdint>
#include <memory>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "cli/recording_command.hpp"
#include "io/recording/recording_merge.hpp"

namespace owsim::cli {
namespace {

void run_merge(const RecordingCommandOptions& options) {
  OpenRecording open(options);
  MergeOptions merge;
  merge.out = options.out;
  merge.on_frame = [&](std::uint64_t frames, std::uint64_t pulses) {
    open.progress.frame_done(frames, pulses);
  };
  const MergeReport report = merge_recording(open.decoder, open.scene, open.scenario, merge);
  if (options.quiet) return;
  fmt::print(stderr, "{}", describe(open.decoder.layout(), open.scenario.scan));
  fmt::print(
      stderr,
      "  rays: the simulator's sweep rebuilt in {} frames, β measured from the words in {}\n",
      report.frames_sweep_rebuilt, report.frames_sweep_measured);
  if (report.time_tag_mismatches > 0) {
    fmt::print(stderr, "  {} pulses' time tags disagree with their rebuilt time\n",
               report.time_tag_mismatches);
  }
  fmt::print(stderr,
             "{} of {} words changed: {} synthetic returns written, {} recorded first returns "
             "moved to counter 2, {} recorded returns hidden by synthetic solids, {} pushed out → "
             "{}\n",
             report.words_changed, report.pulses, report.synthetic_returns, report.recorded_moved,
             report.recorded_hidden, report.recorded_dropped, options.out.string());
}

}  // namespace

void add_merge_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<RecordingCommandOptions>();
  CLI::App* command = app.add_subcommand("merge", "put a scenario's objects into a recording");
  add_recording_options(
      *command, *options,
      {"RECORDING", "scenario file: the sensor, its mount, the trajectory, the objects to add",
       "the merged recording (same format)"});
  command->add_option("--seed", options->overrides.seed, "override the scenario's seed")
      ->check(seed_number());
  command->add_flag("--no-noise", options->overrides.no_noise,
                    "range noise and receiver noise off");
  command->footer(
      "Where a synthetic return is nearer than the recorded first return (or the pulse had none) "
      "its count goes to counter 1 and the recorded return moves to counter 2 (MilOWS); a "
      "synthetic pole, tree or ground hit hides the recorded returns behind it. Every other bit "
      "of every word is kept. The scenario's terrain is traced too: give it `terrain: none` "
      "unless the ground is to be added.");
  command->callback([options] { run_merge(*options); });
}

}  // namespace owsim::cli
