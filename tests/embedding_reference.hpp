#pragma once
// What `owsim run` writes for the embedding tests to compare against: every bundled example and a
// HELLAS scenario (single_span flown by HELLAS), run for a few frames into flight.d64 /
// flight.hellas and points.csv, cut into frames. The C++ facade, the C ABI and the Python module
// must return the same words and rows frame for frame.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace owsim::test {

inline constexpr std::int64_t kReferenceFrames = 3;
inline constexpr std::size_t kPulsesPerFrame = 20'352;

// The bundled examples and a HELLAS scenario, by name → scenario file. The HELLAS one is
// single_span.yaml with `model: hellas`, written into `folder`.
inline std::map<std::string, std::filesystem::path> reference_scenarios(
    const std::filesystem::path& folder) {
  const std::filesystem::path examples = std::filesystem::path(OWSIM_SOURCE_DIR) / "examples";
  std::map<std::string, std::filesystem::path> scenarios;
  for (const char* name : {"single_span", "pylon_line", "corridor", "hellsim_flight"}) {
    scenarios[name] = examples / (std::string(name) + ".yaml");
  }
  std::string text = read_whole_file(examples / "single_span.yaml");
  const std::string milows = "model: milows";
  text.replace(text.find(milows), milows.size(), "model: hellas");
  text.replace(text.find("name: single_span"), 17, "name: single_span_hellas");
  const std::filesystem::path hellas = folder / "single_span_hellas.yaml";
  std::ofstream(hellas) << text;
  scenarios["single_span_hellas"] = hellas;
  return scenarios;
}

// `owsim run SCENARIO --frames 3 --outputs d64,points` cut into frames.
struct ReferenceRun {
  std::size_t word_size = 8;
  std::vector<std::string> frame_words;              // each frame's word bytes
  std::vector<std::vector<std::string>> frame_rows;  // each frame's points.csv rows
};

inline ReferenceRun reference_run(const std::filesystem::path& scenario,
                                  const std::filesystem::path& out) {
  const CliResult result =
      run_cli({"run", scenario.string(), "--frames", std::to_string(kReferenceFrames), "--outputs",
               "d64,points", "--quiet", "--out", out.string()},
              std::filesystem::current_path());
  if (result.exit_status != 0) throw std::runtime_error(result.command + ": " + result.err);
  ReferenceRun run;
  std::string words;
  if (std::filesystem::exists(out / "flight.hellas")) {
    run.word_size = 4;
    words = read_whole_file(out / "flight.hellas").substr(4);  // after the header word
  } else {
    words = read_whole_file(out / "flight.d64");
  }
  const std::size_t frame_bytes = kPulsesPerFrame * run.word_size;
  for (std::int64_t k = 0; k < kReferenceFrames; ++k) {
    run.frame_words.push_back(words.substr(static_cast<std::size_t>(k) * frame_bytes, frame_bytes));
  }
  run.frame_rows.resize(kReferenceFrames);
  std::istringstream csv(read_whole_file(out / "points.csv"));
  std::string row;
  std::getline(csv, row);  // the header
  while (std::getline(csv, row)) {
    const auto frame = std::stoll(row.substr(0, row.find(',')));
    run.frame_rows.at(static_cast<std::size_t>(frame)).push_back(row);
  }
  return run;
}

}  // namespace owsim::test
