#pragma once
// `owsim view`: one self-contained page (report.html) showing a flight folder that `owsim run`,
// `owsim decode` or `owsim merge` + `decode` wrote — the summary and ground truth, a frame player
// of range images, a map and a 3D point cloud (INTERFACE.md "`owsim view`"). What the page holds
// and how it is laid out: io/report/report_page.hpp; what it shows and leaves out: docs/view.md.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace owsim {

struct FlightReportOptions {
  std::filesystem::path out;  // empty: <folder>/report.html
  // draws its wires, poles, trees and meshes; default: the folder's scenario.yaml, if any
  std::optional<std::filesystem::path> scenario;
  std::uint64_t max_points = 2'000'000;  // 3D points carried by the page
  int max_frames = 400;                  // range images carried by the page
  std::size_t max_objects = 5'000;       // rows of the ground-truth table
};

struct FlightReport {
  std::filesystem::path file;
  std::uint64_t bytes = 0;
  std::uint64_t points_total = 0, points_shown = 0;
  std::int64_t frames_total = 0, frames_shown = 0;
  std::vector<std::string> notes;  // what the page leaves out and why, one sentence each
};

// Reads the folder and writes the page (atomically). Throws owsim::Error with one line naming the
// folder or file and the problem: a folder that is not an owsim output, an unreadable or malformed
// file in it, a bad scenario, options out of range.
FlightReport write_flight_report(const std::filesystem::path& folder,
                                 const FlightReportOptions& options = {});

}  // namespace owsim
