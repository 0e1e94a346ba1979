#pragma once
// `--detections PATH` and `--gate-m G` of `owsim pd` and `owsim roc`: a detector's warnings as the
// evidence instead of the returns (evaluation/warned_frames.hpp, docs/evidence.md "Warnings as the
// evidence").
#include <CLI/CLI.hpp>
#include <filesystem>

namespace owsim::cli {

inline void add_warning_options(CLI::App* command, std::filesystem::path& detections,
                                double& gate_m) {
  command->add_option(
      "--detections", detections,
      "warnings instead of returns: a detections file (run), a folder of "
      "<member>.csv (sweep), or the run or sweep folder itself (its detections.csv)");
  command->add_option("--gate-m", gate_m,
                      "with --detections: a warning within this of an object's surface hit it "
                      "(default 5)");
}

}  // namespace owsim::cli
