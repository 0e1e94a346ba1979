// owsim decode FILE --scenario S [--trajectory T] --out DIR — a recording back into points, what
// a replay tool shows a person (INTERFACE.md; io/recording_decoder_points.hpp).
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
#include "io/recording_decoder_points.hpp"
#include "io/recording_decoder_scene.hpp"

namespace owsim::cli {
namespace {

struct DecodeOptions {
  std::filesystem::path recording;
  std::filesystem::path scenario;
  std::filesystem::path out;
  RecordingScenarioOverrides overrides;
  std::optional<std::string> format;
  std::optional<double> start_s;
  int threads = 0;
  bool no_labels = false;
  bool quiet = false;
};

void run_decode(const DecodeOptions& options) {
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  const Scenario scenario = load_recording_scenario(options.scenario, options.overrides);
  check_recording_format(options.recording, options.format, scenario);
  RecordingDecoder decoder(options.recording, scenario.scan, {options.start_s});
  const RecordingScene scene(scenario, decoder.layout());
  RecordingProgress progress(!options.quiet, decoder.layout().frames);
  DecodePointsOptions points;
  points.directory = options.out;
  points.label_from_scene = !options.no_labels;
  points.on_frame = [&](std::uint64_t frames, std::uint64_t pulses) {
    progress.frame_done(frames, pulses);
  };
  const DecodeReport report = decode_recording_points(decoder, scene, scenario, points);
  if (options.quiet) return;
  fmt::print(stderr, "{}", describe(decoder.layout(), scenario.scan));
  if (report.time_tag_mismatches > 0) {
    fmt::print(stderr, "  {} pulses' time tags disagree with their rebuilt time\n",
               report.time_tag_mismatches);
  }
  if (scenario.scan.model == SensorModel::hellas) {
    const auto& by = report.frames_by_beta_source;
    fmt::print(stderr,
               "  β from the NI mark in {} frames, the header in {}, the nominal sweep in {}\n",
               by[static_cast<std::size_t>(MirrorBetaSource::ni_mark)],
               by[static_cast<std::size_t>(MirrorBetaSource::header)],
               by[static_cast<std::size_t>(MirrorBetaSource::nominal)]);
  }
  fmt::print(stderr,
             "{} points ({} second returns, {} labelled from the scenario's objects) → {}\n",
             report.points, report.second_returns, report.labelled_points, options.out.string());
}

}  // namespace

void add_decode_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<DecodeOptions>();
  CLI::App* command =
      app.add_subcommand("decode", "a recording back into points (points.csv, .las, .ply)");
  command->add_option("FILE", options->recording, "a MilOWS (.d64) or HELLAS (.hellas) word file")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--scenario", options->scenario,
                   "scenario file: the sensor, its mount, the trajectory, the objects")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "output folder for the point files")->required();
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
  command->add_option("--threads", options->threads, "worker threads (default: every core)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--no-labels", options->no_labels,
                    "do not label returns from the scenario's objects (class `unknown`)");
  command->add_flag("--quiet", options->quiet, "no report on stderr");
  command->footer(
      "Pulses are numbered from the first frame gate and timed from their time tags (exactly "
      "start_s + n/PRF when the tags fall on the scenario's pulse grid, as owsim's do); β comes "
      "from the motor encoder (MilOWS) or the NI mark (HELLAS). What the recording holds — "
      "partial first/last frames, tag wraps, how time was rebuilt — is reported on stderr.");
  command->callback([options] { run_decode(*options); });
}

}  // namespace owsim::cli
