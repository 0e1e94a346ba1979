// owsim detect RUN_DIR [--out DIR] [--quiet] — the reference obstacle detector over a run folder's
// recorded words and navigation (INTERFACE.md "Obstacle warnings", DETECTION-SPEC;
// io/detections/recording_detections.hpp): detections.csv, the same bytes `owsim run --outputs
// …,detections` writes in the folder.
#include <fmt/core.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "cli/commands.hpp"
#include "io/detections/recording_detections.hpp"

namespace owsim::cli {
namespace {

struct DetectOptions {
  std::filesystem::path folder;
  std::filesystem::path out;
  bool quiet = false;
};

void run_detect(const DetectOptions& options) {
  const std::filesystem::path out = options.out.empty() ? options.folder : options.out;
  const auto start = std::chrono::steady_clock::now();
  const DetectionReport report = detect_run_folder(options.folder, out);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.quiet) return;
  fmt::print(stderr,
             "{} frames, {} returns: {} warnings from {} tracks in {:.2f} s; written to {}\n",
             report.frames, report.returns, report.warnings, report.tracks, wall_s,
             (out / "detections.csv").string());
}

}  // namespace

void add_detect_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<DetectOptions>();
  CLI::App* command = app.add_subcommand(
      "detect",
      "obstacle warnings (wire, pole, tree) from a run folder's recorded words and navigation, "
      "by the reference detector of the scenario's detector: section");
  command->add_option("RUN_DIR", options->folder, "a run folder (scenario.yaml and its words)")
      ->required();
  command->add_option("--out", options->out, "where detections.csv goes (default RUN_DIR)");
  command->add_flag("--quiet", options->quiet, "print nothing on success");
  command->callback([options] { run_detect(*options); });
}

}  // namespace owsim::cli
