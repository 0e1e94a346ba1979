#pragma once
// trajectory.csv of `owsim run` read back for `owsim view`: the sensor pose at every frame start
// (INTERFACE.md: time_s, e_m, n_m, u_m, roll_deg, pitch_deg, heading_deg used; lat/lon/h not).
#include <array>
#include <filesystem>
#include <vector>

namespace owsim {

struct ReportTrajectory {
  // time_s, e_m, n_m, u_m, roll_deg, pitch_deg, heading_deg of each row, in file order.
  std::vector<std::array<double, 7>> rows;
};

// Throws owsim::Error naming file:line and the column for a missing column or a bad number.
[[nodiscard]] ReportTrajectory read_report_trajectory(const std::filesystem::path& path);

}  // namespace owsim
