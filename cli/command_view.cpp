// owsim view DIR [--scenario S] [--out FILE] — a flight folder as one self-contained page
// (INTERFACE.md "`owsim view`"; owsim/flight_report.hpp).
#include <fmt/core.h>

#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "owsim/flight_report.hpp"

namespace owsim::cli {
namespace {

struct ViewOptions {
  std::filesystem::path folder;
  std::filesystem::path out;
  std::filesystem::path scenario;
  FlightReportOptions report;
  bool quiet = false;
};

void run_view(const ViewOptions& options) {
  FlightReportOptions report_options = options.report;
  report_options.out = options.out;
  if (!options.scenario.empty()) report_options.scenario = options.scenario;
  const FlightReport report = write_flight_report(options.folder, report_options);
  if (options.quiet) return;
  for (const std::string& note : report.notes) fmt::print(stderr, "  {}\n", note);
  fmt::print(stderr, "{} ({:.1f} MB): {} of {} returns, {} of {} frames\n", report.file.string(),
             static_cast<double>(report.bytes) / 1e6, report.points_shown, report.points_total,
             report.frames_shown, report.frames_total);
}

}  // namespace

void add_view_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command = app.add_subcommand(
      "view", "a flight folder as one page that opens offline: summary, frames, map, 3D");
  command->add_option("DIR", options->folder, "a folder owsim run, decode or merge + decode wrote")
      ->required();
  command->add_option("--out", options->out, "the page to write (default: DIR/report.html)");
  command->add_option("--scenario", options->scenario,
                      "the flight's scenario: draws its wires, poles, trees and meshes, and sets "
                      "the sensor's frame layout");
  command
      ->add_option("--max-points", options->report.max_points,
                   "most returns the 3D view carries (rare classes kept whole; default 2000000)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100'000'000}));
  command
      ->add_option("--max-frames", options->report.max_frames,
                   "most frames the frame player carries, evenly spread (default 400)")
      ->check(CLI::Range(1, 100'000));
  command->add_flag("--quiet", options->quiet, "print nothing on success");
  command->callback([options] { run_view(*options); });
}

}  // namespace owsim::cli
