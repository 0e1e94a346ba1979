#pragma once
// What `owsim decode` and `owsim merge` share (INTERFACE.md): their common options — the
// recording, the scenario and a navigation file replacing its trajectory, the output, the word
// format, the start hint, the worker threads, --quiet — and what both do before their own work.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>

#include "cli/progress_line.hpp"
#include "io/recording/recording_decoder.hpp"
#include "io/recording/recording_decoder_scene.hpp"
#include "io/scenario/scenario.hpp"

namespace owsim::cli {

struct RecordingCommandOptions {
  std::filesystem::path recording;
  std::filesystem::path scenario;
  std::filesystem::path out;
  RecordingScenarioOverrides overrides;  // --trajectory, --trajectory-format, the command's own
  std::optional<std::string> format;     // "d64" | "hellas"
  std::optional<double> start_s;
  int threads = 0;  // 0: every core
  bool quiet = false;
};

// What differs between the two commands' help for the common options.
struct RecordingOptionHelp {
  std::string recording_name;  // the positional argument: "FILE", "RECORDING"
  std::string scenario;        // --scenario
  std::string out;             // --out
};

// Registers the common options on `command`, bound to `options` (which must outlive the parse).
void add_recording_options(CLI::App& command, RecordingCommandOptions& options,
                           const RecordingOptionHelp& help);

// The recording opened as both commands open it: the worker threads capped, the scenario loaded
// with the overrides, the recording's format checked against it, its layout read (the decoder
// refuses an unsound recording), the scene built over its time span, and a progress line over its
// frames. Throws owsim::Error naming the file at fault.
struct OpenRecording {
  explicit OpenRecording(const RecordingCommandOptions& options);

  tbb::global_control parallelism;
  Scenario scenario;
  RecordingDecoder decoder;
  RecordingScene scene;
  ProgressLine progress;
};

}  // namespace owsim::cli
