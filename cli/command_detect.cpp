// owsim detect RUN_DIR|SWEEP_DIR [--out DIR] [--quiet] — the reference obstacle detector over the
// recorded words and navigation of a run folder, or of every member of a sweep folder
// (INTERFACE.md "Obstacle warnings", DETECTION-SPEC; io/detections/recording_detections.hpp):
// detections.csv, the same bytes `owsim run --outputs …,detections` writes in the folder. A run's
// goes to DIR/detections.csv (default the run folder); a sweep's members' to their own folders, or
// with --out to DIR/<member>.csv — the layout `owsim score --detections DIR` reads.
#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <vector>

#include "cli/commands.hpp"
#include "evaluation/truth_table.hpp"
#include "io/detections/recording_detections.hpp"

namespace owsim::cli {
namespace {

struct DetectOptions {
  std::filesystem::path folder;
  std::filesystem::path out;
  bool quiet = false;
};

struct DetectJob {
  std::filesystem::path run;
  std::filesystem::path csv;
};

std::vector<DetectJob> detect_jobs(const DetectOptions& options) {
  if (!std::filesystem::is_regular_file(options.folder / "sweep.csv")) {
    const std::filesystem::path out = options.out.empty() ? options.folder : options.out;
    return {{options.folder, out / "detections.csv"}};
  }
  std::vector<DetectJob> jobs;
  for (const CampaignFlight& member : campaign_flights(options.folder)) {
    (void)run_recording(member.directory);  // every member checked before any is written
    jobs.push_back({member.directory, options.out.empty()
                                          ? member.directory / "detections.csv"
                                          : options.out / (member.name + ".csv")});
  }
  return jobs;
}

void run_detect(const DetectOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  DetectionReport total;
  const std::vector<DetectJob> jobs = detect_jobs(options);
  for (const DetectJob& job : jobs) total += detect_run_folder(job.run, job.csv);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.quiet) return;
  const std::string written = jobs.size() == 1 ? jobs.front().csv.string()
                                               : jobs.front().csv.parent_path().string() + "…";
  fmt::print(stderr,
             "{} flight{}, {} frames, {} returns: {} warnings from {} tracks in {:.2f} s; written "
             "to {}\n",
             jobs.size(), jobs.size() == 1 ? "" : "s", total.frames, total.returns, total.warnings,
             total.tracks, wall_s, written);
}

}  // namespace

void add_detect_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<DetectOptions>();
  CLI::App* command = app.add_subcommand(
      "detect",
      "obstacle warnings (wire, pole, tree) from a run's recorded words and navigation, by the "
      "reference detector of the scenario's detector: section");
  command->add_option("DIR", options->folder, "a run folder, or a sweep folder (every member)")
      ->required();
  command->add_option("--out", options->out,
                      "where detections.csv goes (default the run folder); for a sweep, a folder "
                      "of <member>.csv (default each member's folder)");
  command->add_flag("--quiet", options->quiet, "print nothing on success");
  command->callback([options] { run_detect(*options); });
}

}  // namespace owsim::cli
