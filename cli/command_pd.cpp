// owsim pd DIR [--target ID | --class C] [--returns K] [--window-s W] [--bins LO:HI:STEP]
//              [--confidence C] [--out DIR] — detection probability versus range from a run or
// sweep folder's ground truth (INTERFACE.md "Ground truth and detection evidence";
// evaluation/pd_report.hpp).
#include <fmt/core.h>

#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/warning_options.hpp"
#include "evaluation/pd_report.hpp"

namespace owsim::cli {
namespace {

struct PdCommandOptions {
  PdOptions pd;
  std::string target;
  std::string target_class;
  std::string bins = "0:1300:50";
  std::filesystem::path out;
  std::filesystem::path detections;
  bool quiet = false;
};

std::string range_text(const std::optional<double>& range_m) {
  return range_m ? fmt::format("{:.0f} m", *range_m) : std::string("not demonstrated");
}

void run_pd(PdCommandOptions& options) {
  PdOptions& pd = options.pd;
  if (!options.target.empty()) pd.target_id = options.target;
  if (!options.target_class.empty()) pd.target_class = options.target_class;
  pd.bins = parse_range_bins(options.bins);
  if (!options.out.empty()) pd.out = options.out;
  if (!options.detections.empty()) pd.detections = options.detections;
  const PdReport report = write_pd_report(pd);
  if (options.quiet) return;
  fmt::print(stderr,
             "{}: {} trials in {} flights ({} detected); written to {}/pd.csv, pd.json, "
             "pd.svg\n",
             report.target, report.curve.trials, report.flights, report.curve.trials_detected,
             report.directory.string());
  for (std::size_t p = 0; p < kDemonstratedProbabilities.size(); ++p) {
    fmt::print(stderr, "  Pd within {} s ≥ {} demonstrated (lower bound, {} %) to {}\n",
               pd.criterion.window_s, kDemonstratedProbabilities[p], pd.confidence * 100.0,
               range_text(report.curve.demonstrated_range_m[p]));
  }
  fmt::print(stderr, "  the sensor's false returns: {} in {} pulses, {:.3g} per second of flight\n",
             report.false_returns.false_returns, report.false_returns.pulses,
             report.false_returns.per_s());
  if (report.warnings) {
    fmt::print(stderr,
               "  warnings: {} rows of {} tracks; {} false warnings in {:.3g} flight hours, {:.3g} "
               "per flight hour\n",
               report.warnings->rows, report.warnings->tracks, report.warnings->false_warnings,
               report.warnings->hours, report.warnings->false_warnings_per_hour());
  }
}

}  // namespace

void add_pd_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<PdCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "pd",
      "detection probability versus range with confidence intervals, from ground truth (of the "
      "returns, or with --detections of a detector's warnings)");
  command->add_option("DIR", options->pd.folder, "a run folder or a sweep folder")->required();
  auto* target = command->add_option("--target", options->target, "one object, by its id");
  command
      ->add_option("--class", options->target_class,
                   "every object of this class, pooled (default wire)")
      ->excludes(target);
  command
      ->add_option("--returns", options->pd.criterion.returns,
                   "returns on the target a detection needs (with --detections: frames warning of "
                   "it; default 1)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1'000'000}));
  command->add_option("--window-s", options->pd.criterion.window_s,
                      "seconds the returns may take (default 1)");
  command->add_option("--bins", options->bins,
                      "range bins LO:HI:STEP in metres (default 0:1300:50)");
  command->add_option("--confidence", options->pd.confidence,
                      "two-sided confidence of the intervals (default 0.95)");
  command->add_option("--out", options->out, "where pd.csv, pd.json and pd.svg go (default DIR)");
  add_warning_options(command, options->detections, options->pd.gate_m);
  command->add_flag("--quiet", options->quiet, "print nothing on success");
  command->callback([options] { run_pd(*options); });
}

}  // namespace owsim::cli
