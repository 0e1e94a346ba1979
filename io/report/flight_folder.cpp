#include "io/report/flight_folder.hpp"

#include <system_error>

#include "geometry/error.hpp"

namespace owsim {
namespace {

std::optional<std::filesystem::path> file_in(const std::filesystem::path& directory,
                                             const char* name) {
  std::error_code error;
  const std::filesystem::path path = directory / name;
  if (std::filesystem::is_regular_file(path, error)) return path;
  return std::nullopt;
}

}  // namespace

FlightFolder find_flight_folder(const std::filesystem::path& directory) {
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    throw file_error(directory.string(),
                     "not a folder (owsim view takes the folder a run, a "
                     "decode or a merge + decode wrote)");
  }
  FlightFolder folder;
  folder.directory = directory;
  folder.summary_json = file_in(directory, "summary.json");
  folder.trajectory_csv = file_in(directory, "trajectory.csv");
  folder.points_csv = file_in(directory, "points.csv");
  folder.points_ply = file_in(directory, "points.ply");
  folder.points_las = file_in(directory, "points.las");
  folder.words = file_in(directory, "flight.d64");
  if (!folder.words) {
    folder.words = file_in(directory, "flight.hellas");
    folder.hellas_words = folder.words.has_value();
  }
  if (!folder.summary_json && !folder.trajectory_csv && !folder.points_csv && !folder.points_ply &&
      !folder.points_las && !folder.words) {
    throw input_error(directory.string(),
                      "not an owsim output folder: no summary.json, trajectory.csv, "
                      "points.csv/.las/.ply, flight.d64 or flight.hellas in it");
  }
  return folder;
}

}  // namespace owsim
