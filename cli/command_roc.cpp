// owsim roc DIR [--target ID | --class C] [--range LO:HI] [--by KEY] [--returns K] [--window-s W]
//               [--confidence C] [--out DIR] — Pd within W against the sensor's false returns
// per second over a sweep that varies a key (INTERFACE.md "Receiver noise and sunlight";
// evaluation/roc_report.hpp).
#include <fmt/core.h>

#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/warning_options.hpp"
#include "evaluation/roc_report.hpp"

namespace owsim::cli {
namespace {

struct RocCommandOptions {
  RocOptions roc;
  std::string target;
  std::string target_class;
  std::string range = "700:800";
  std::filesystem::path out;
  std::filesystem::path detections;
  bool quiet = false;
};

void run_roc(RocCommandOptions& options) {
  RocOptions& roc = options.roc;
  if (!options.target.empty()) roc.target.id = options.target;
  if (!options.target_class.empty()) roc.target.object_class = options.target_class;
  parse_roc_range(options.range, roc);
  if (!options.out.empty()) roc.out = options.out;
  if (!options.detections.empty()) roc.detections = options.detections;
  const RocReport report = write_roc_report(roc);
  if (options.quiet) return;
  fmt::print(stderr,
             "{}: {} values of {} over {} flights; written to {}/roc.csv, roc.json, roc.svg\n",
             report.target, report.rows.size(), roc.by, report.flights, report.directory.string());
  for (const RocRow& row : report.rows) {
    const std::string pd =
        row.windows == 0
            ? std::string("no windows")
            : fmt::format(
                  "Pd within {} s {:.4f} [{:.4f}, {:.4f}] over {} windows", roc.criterion.window_s,
                  static_cast<double>(row.windows_detected) / static_cast<double>(row.windows),
                  row.window_interval.lower, row.window_interval.upper, row.windows);
    if (row.warnings) {
      fmt::print(stderr, "  {} = {}: {}; {} false warnings, {:.4g} per flight hour\n", roc.by,
                 row.value, pd, row.warnings->false_warnings,
                 row.warnings->false_warnings_per_hour());
    } else {
      fmt::print(stderr, "  {} = {}: {}; {:.4g} false returns/s\n", roc.by, row.value, pd,
                 row.false_returns.per_s());
    }
  }
}

}  // namespace

void add_roc_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<RocCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "roc", "Pd against false returns per second over a sweep that varies the threshold");
  command->add_option("DIR", options->roc.folder, "a sweep folder")->required();
  auto* target = command->add_option("--target", options->target, "one object, by its id");
  command
      ->add_option("--class", options->target_class,
                   "every object of this class, pooled (default wire)")
      ->excludes(target);
  command->add_option("--range", options->range,
                      "the range bin LO:HI in metres of the windows' first frame (default "
                      "700:800)");
  command->add_option("--by", options->roc.by,
                      "the varied key whose values make the rows (default sensor.threshold)");
  command
      ->add_option("--returns", options->roc.criterion.returns,
                   "returns on the target a detection needs (default 1)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1'000'000}));
  command->add_option("--window-s", options->roc.criterion.window_s,
                      "seconds the returns may take (default 1)");
  command->add_option("--confidence", options->roc.confidence,
                      "two-sided confidence of the intervals (default 0.95)");
  command->add_option("--out", options->out,
                      "where roc.csv, roc.json and roc.svg go (default DIR)");
  add_warning_options(command, options->detections, options->roc.gate_m);
  command->add_flag("--quiet", options->quiet, "print nothing on success");
  command->callback([options] { run_roc(*options); });
}

}  // namespace owsim::cli
