// owsim score DIR --detections FILE|FOLDER [--gate-m G] [--confidence C] [--bins LO:HI:STEP]
//                 [--out DIR] — a detector's output scored against a run or sweep folder's truth
// (INTERFACE.md "Ground truth and detection evidence"; evaluation/detector_score.hpp).
#include <fmt/core.h>

#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "evaluation/detector_score.hpp"
#include "evaluation/pd_report.hpp"

namespace owsim::cli {
namespace {

struct ScoreCommandOptions {
  ScoreOptions score;
  std::string bins = "0:1300:50";
  std::filesystem::path out;
  bool quiet = false;
};

void run_score(ScoreCommandOptions& options) {
  ScoreOptions& score = options.score;
  score.bins = parse_range_bins(options.bins);
  if (!options.out.empty()) score.out = options.out;
  const ScoreReport report = write_score_report(score);
  if (options.quiet) return;
  fmt::print(stderr,
             "{} detections in {} flights ({:.3f} h): {} false alarms; written to "
             "{}/score.json, score.csv\n",
             report.detections, report.flights, report.flight_hours, report.false_alarms,
             report.directory.string());
  for (const auto& [name, of_class] : report.by_class) {
    fmt::print(stderr, "  {}: {} of {} in view detected, Pd {:.3f} [{:.3f}, {:.3f}]\n", name,
               of_class.detected, of_class.objects,
               of_class.objects > 0
                   ? static_cast<double>(of_class.detected) / static_cast<double>(of_class.objects)
                   : 0.0,
               of_class.interval.lower, of_class.interval.upper);
  }
  if (report.object_confusion.empty()) return;
  // Objects in view by their class and the class they were warned as.
  fmt::print(stderr, "  objects in view, warned as:");
  for (const auto& [warned, count] : report.object_confusion.begin()->second) {
    fmt::print(stderr, " {:>6}", warned);
  }
  fmt::print(stderr, "\n");
  for (const auto& [truth, row] : report.object_confusion) {
    fmt::print(stderr, "  {:>24}:", truth);
    for (const auto& [warned, count] : row) fmt::print(stderr, " {:>6}", count);
    fmt::print(stderr, "\n");
  }
}

}  // namespace

void add_score_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<ScoreCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "score",
      "a detector's output scored against the ground truth: Pd, warning time, false alarms");
  command->add_option("DIR", options->score.folder, "a run folder or a sweep folder")->required();
  command
      ->add_option("--detections", options->score.detections,
                   "CSV of time_s and e_m,n_m,u_m or lat_deg,lon_deg,h_m (optional class, "
                   "track); for a sweep, a folder of <member>.csv")
      ->required();
  command->add_option("--gate-m", options->score.gate_m,
                      "how near an object's surface a detection hits it (default 5 m)");
  command->add_option("--confidence", options->score.confidence,
                      "two-sided confidence of the intervals (default 0.95)");
  command->add_option("--bins", options->bins,
                      "range bins of Pd versus range, LO:HI:STEP in metres (default 0:1300:50)");
  command->add_option("--out", options->out, "where score.json and score.csv go (default DIR)");
  command->add_flag("--quiet", options->quiet, "print nothing on success");
  command->callback([options] { run_score(*options); });
}

}  // namespace owsim::cli
