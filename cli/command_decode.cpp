// owsim decode FILE --scenario S [--trajectory T] --out DIR — a recording back into points, what
// a replay tool shows a person (INTERFACE.md; io/recording/recording_decoder_points.hpp).
#include <fmt/core.h>

#include <cstdint>
#include <memory>
#include <set>
#include <string>

#include "cli/commands.hpp"
#include "cli/recording_command.hpp"
#include "geometry/error.hpp"
#include "io/recording/recording_decoder_points.hpp"
#include "io/run/output_kind.hpp"

namespace owsim::cli {
namespace {

struct DecodeOptions : RecordingCommandOptions {
  bool no_labels = false;
  std::string outputs = "points";
};

void run_decode(const DecodeOptions& options) {
  const std::set<OutputKind> outputs = parse_output_list(options.outputs);
  for (const OutputKind kind : outputs) {
    if (kind != OutputKind::csv && kind != OutputKind::las && kind != OutputKind::ply) {
      throw input_error("--outputs", "decode writes points only: csv, las, ply or points, got " +
                                         options.outputs);
    }
  }
  OpenRecording open(options);
  DecodePointsOptions points;
  points.directory = options.out;
  points.csv = outputs.contains(OutputKind::csv);
  points.las = outputs.contains(OutputKind::las);
  points.ply = outputs.contains(OutputKind::ply);
  points.label_from_scene = !options.no_labels;
  points.on_frame = [&](std::uint64_t frames, std::uint64_t pulses) {
    open.progress.frame_done(frames, pulses);
  };
  const DecodeReport report =
      decode_recording_points(open.decoder, open.scene, open.scenario, points);
  if (options.quiet) return;
  const ScanParams& scan = open.scenario.scan;
  fmt::print(stderr, "{}", describe(open.decoder.layout(), scan));
  if (report.time_tag_mismatches > 0) {
    fmt::print(stderr, "  {} pulses' time tags disagree with their rebuilt time\n",
               report.time_tag_mismatches);
  }
  if (scan.model == SensorModel::hellas) {
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
  add_recording_options(
      *command, *options,
      {"FILE", "scenario file: the sensor, its mount, the trajectory, the objects",
       "output folder for the point files"});
  command->add_flag("--no-labels", options->no_labels,
                    "do not label returns from the scenario's objects (class `unknown`)");
  command->add_option("--outputs", options->outputs,
                      "comma list of csv, las, ply, or points for all three (default: points)");
  command->footer(
      "Pulses are numbered from the first frame gate and timed from their time tags (exactly "
      "start_s + n/PRF when the tags fall on the scenario's pulse grid, as owsim's do); β comes "
      "from the motor encoder (MilOWS) or the NI mark (HELLAS). What the recording holds — "
      "partial first/last frames, tag wraps, how time was rebuilt — is reported on stderr.");
  command->callback([options] { run_decode(*options); });
}

}  // namespace owsim::cli
