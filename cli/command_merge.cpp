// owsim merge RECORDING --scenario S [--trajectory T] --out FILE — put a scenario's objects into a
// recording (INTERFACE.md; SENSOR-SPEC §9; io/recording_merge.hpp).
#include <fmt/core.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli/command_decode_progress.hpp"
#include "cli/commands.hpp"
#include "io/recording_decoder.hpp"
#include "io/recording_decoder_scene.hpp"
#include "io/recording_merge.hpp"

namespace owsim::cli {
namespace {

struct MergeCommandOptions {
  std::filesystem::path recording;
  std::filesystem::path scenario;
  std::filesystem::path out;
  RecordingScenarioOverrides overrides;
  std::optional<std::string> format;
  std::optional<double> start_s;
  int threads = 0;
  bool quiet = false;
};

void run_merge(const MergeCommandOptions& options) {
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  const Scenario scenario = load_recording_scenario(options.scenario, options.overrides);
  check_recording_format(options.recording, options.format, scenario);
  RecordingDecoder decoder(options.recording, scenario.scan, {options.start_s});
  const RecordingScene scene(scenario, decoder.layout());
  RecordingProgress progress(!options.quiet, decoder.layout().frames);
  MergeOptions merge;
  merge.out = options.out;
  merge.on_frame = [&](std::uint64_t frames, std::uint64_t pulses) {
    progress.frame_done(frames, pulses);
  };
  const MergeReport report = merge_recording(decoder, scene, scenario, merge);
  if (options.quiet) return;
  fmt::print(stderr, "{}", describe(decoder.layout(), scenario.scan));
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
  auto options = std::make_shared<MergeCommandOptions>();
  CLI::App* command = app.add_subcommand("merge", "put a scenario's objects into a recording");
  command
      ->add_option("RECORDING", options->recording, "a MilOWS (.d64) or HELLAS (.hellas) word file")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--scenario", options->scenario,
                   "scenario file: the sensor, its mount, the trajectory, the objects to add")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "the merged recording (same format)")->required();
  command
      ->add_option("--trajectory", options->overrides.trajectory,
                   "navigation file instead of the scenario's trajectory")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--trajectory-format", options->overrides.trajectory_format,
                   "hellsim | csv | sbet (default: csv for .csv, else hellsim)")
      ->check(CLI::IsMember({"hellsim", "csv", "sbet"}));
  command->add_option("--format", options->format, "d64 | hellas, when the extension does not say")
      ->check(CLI::IsMember({"d64", "hellas"}));
  command->add_option("--start-s", options->start_s,
                      "approximate time of the first pulse on the trajectory's clock: picks the "
                      "time tags' wrap nearest it (default: the first from trajectory.start_s on)");
  command->add_option("--seed", options->overrides.seed, "override the scenario's seed");
  command->add_flag("--no-noise", options->overrides.no_noise, "range noise off (σ = 0)");
  command->add_option("--threads", options->threads, "worker threads (default: every core)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--quiet", options->quiet, "no report on stderr");
  command->footer(
      "Where a synthetic return is nearer than the recorded first return (or the pulse had none) "
      "its count goes to counter 1 and the recorded return moves to counter 2 (MilOWS); a "
      "synthetic pole, tree or ground hit hides the recorded returns behind it. Every other bit "
      "of every word is kept. The scenario's terrain is traced too: give it `terrain: none` "
      "unless the ground is to be added.");
  command->callback([options] { run_merge(*options); });
}

}  // namespace owsim::cli
