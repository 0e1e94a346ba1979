#pragma once
// What an output folder of `owsim run`, `owsim decode` or `owsim merge` + `decode` holds, as
// `owsim view` needs to know it (INTERFACE.md "`owsim view`"): each file it may draw from, by
// its name in INTERFACE.md "`owsim run` outputs". A folder holding none of them is not an owsim
// output and is refused.
#include <filesystem>
#include <optional>

namespace owsim {

struct FlightFolder {
  std::filesystem::path directory;
  std::optional<std::filesystem::path> summary_json;
  std::optional<std::filesystem::path> trajectory_csv;
  std::optional<std::filesystem::path> points_csv;
  std::optional<std::filesystem::path> points_ply;
  std::optional<std::filesystem::path> points_las;
  std::optional<std::filesystem::path> words;  // flight.d64 or flight.hellas
  bool hellas_words = false;                   // words is flight.hellas
};

// Looks into `directory`. Throws owsim::FileError if it is not a readable folder, owsim::Error
// naming the folder if it holds no summary.json, trajectory.csv, points.csv/.las/.ply or word file.
[[nodiscard]] FlightFolder find_flight_folder(const std::filesystem::path& directory);

}  // namespace owsim
