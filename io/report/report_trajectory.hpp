#pragma once
// trajectory.csv of `owsim run` read back for `owsim view`: the sensor pose at every frame start
// (INTERFACE.md: every column, by name).
#include <filesystem>
#include <vector>

namespace owsim {

struct TrajectoryRow {
  double time_s, lat_deg, lon_deg, h_m, e_m, n_m, u_m, roll_deg, pitch_deg, heading_deg;
};

struct ReportTrajectory {
  std::vector<TrajectoryRow> rows;  // in file order: row k is frame k's start
};

// Throws owsim::Error naming file:line and the column for a missing column or a bad number.
[[nodiscard]] ReportTrajectory read_report_trajectory(const std::filesystem::path& path);

}  // namespace owsim
