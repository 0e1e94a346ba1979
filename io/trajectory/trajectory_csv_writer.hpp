#pragma once
// trajectory.csv: the aircraft's pose at every frame start (INTERFACE.md "`owsim run` outputs"),
// columns time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg — the columns
// io/trajectory/trajectory_csv_reader.hpp reads back, so a written trajectory can be flown again.
//
// One row per Pose given, in the order given. e_m, n_m, u_m are the body origin in the scenario's
// local ENU frame; lat_deg, lon_deg, h_m the same point on WGS-84 (LocalFrame::geodetic_from_enu,
// exact to nanometres); roll, pitch, heading the pose's attitude against the local-level axes at
// the position, as held (not wrapped). Fixed decimals: time 9 (1 ns), lat/lon 9 (≤ 0.11 mm),
// h and e/n/u 4 (0.1 mm), angles 9 (the attitude round-trips to 1e-9°). Rows go through a buffer
// into an AtomicOutputFile: nothing appears under the final name before finish(); checkpoint() and
// resume() let an interrupted run continue the file. Errors throw owsim::Error naming the path.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "geometry/geodetic_frame.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/writer_checkpoint.hpp"
#include "sensor/mounting.hpp"

namespace owsim {

inline constexpr std::string_view kTrajectoryCsvHeader =
    "time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg";

class TrajectoryCsvWriter {
 public:
  // `frame` is the scenario's local frame (copied). Writes the header line.
  TrajectoryCsvWriter(std::filesystem::path final_path, const LocalFrame& frame,
                      AtomicOutputOptions options = {});
  // Continues the temporary file an interrupted writer left at `from` (bytes after it are cut
  // off). Throws owsim::Error naming the path if the temporary is missing or shorter.
  [[nodiscard]] static TrajectoryCsvWriter resume(std::filesystem::path final_path,
                                                  const LocalFrame& frame,
                                                  const WriterCheckpoint& from,
                                                  AtomicOutputOptions options = {});

  void write(const Pose& pose);
  void write(std::span<const Pose> poses);
  // Flushes and renames the file to its final name; nothing may be written afterwards.
  void finish();
  [[nodiscard]] std::uint64_t rows_written() const { return rows_written_; }
  // Hands every row written so far to the kernel; where to resume from.
  [[nodiscard]] WriterCheckpoint checkpoint();

 private:
  TrajectoryCsvWriter(AtomicOutputFile file, const LocalFrame& frame, std::uint64_t rows_written);
  void flush_buffer();

  AtomicOutputFile file_;
  LocalFrame frame_;
  std::string buffer_;
  std::uint64_t rows_written_ = 0;
};

}  // namespace owsim
