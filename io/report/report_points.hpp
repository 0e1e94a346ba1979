#pragma once
// The returns of a flight folder read back for `owsim view`: from points.csv (every column the
// page uses: position, range, class, and the frame, line, fiber and return that place a return in
// its frame's range image) or, without it, from points.ply (position and class only). Held as
// plain arrays, 24 bytes a return, so ten million returns take 240 MB while the page is built.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <istream>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/geodetic_frame.hpp"

namespace owsim {

// A range as the page carries it: decimetres, 1..65535 (6.5 km); 0 for an unknown range.
[[nodiscard]] inline std::uint16_t range_decimetres(float range_m) {
  if (!std::isfinite(range_m)) return 0;
  return static_cast<std::uint16_t>(std::clamp(std::round(range_m * 10.0), 1.0, 65535.0));
}

// Frame numbers a flight folder's files may give (points.csv's frame, summary.json's frames).
inline constexpr std::int64_t kMaxReportFrames = 2'000'000'000;

struct ReportPoints {
  std::string source;                 // "points.csv", "points.ply" or "points.las"
  std::vector<float> e_m, n_m, u_m;   // local East-North-Up from the scenario origin
  std::vector<float> range_m;         // NaN: not in the file (PLY)
  std::vector<std::uint8_t> surface;  // SurfaceClass code, kUnknownSurface if unknown
  // Where each return sits in its frame (points.csv only; empty for PLY).
  std::vector<std::int32_t> frame;
  std::vector<std::int16_t> line, fiber;
  std::vector<std::uint8_t> return_number;
  // By frame: the earliest return's pulse time, for frames with a return that has one. Sized by
  // the frames the file holds, not by their numbers.
  std::unordered_map<std::int32_t, double> frame_first_time_s;

  bool pulses_known = false;  // frame, line, fiber and return are filled

  [[nodiscard]] std::size_t size() const { return e_m.size(); }
  // One return without its place in a frame (PLY, LAS).
  void add(double e, double n, double u, float range, std::uint8_t surface_code) {
    e_m.push_back(static_cast<float>(e));
    n_m.push_back(static_cast<float>(n));
    u_m.push_back(static_cast<float>(u));
    range_m.push_back(range);
    surface.push_back(surface_code);
  }
};

// Calls each(record) for `count` records of `bytes` bytes each, read from `in` in blocks. Throws
// owsim::Error naming `path` on a short read.
void for_each_record(std::istream& in, std::uint64_t count, std::size_t bytes,
                     const std::filesystem::path& path,
                     const std::function<void(const char* record)>& each);

// points.csv of INTERFACE.md, columns found by their header names (e_m, n_m, u_m required; frame,
// line, fiber, return, time_s, range_m and class used when present). Throws owsim::Error naming
// file:line and the column for a missing column or a cell that is not a number / class.
[[nodiscard]] ReportPoints read_report_points_csv(const std::filesystem::path& path);

// points.ply as owsim writes it (binary little-endian: double x y z, float intensity, uchar
// class: owsim's class codes 0..5, 7 noise; others unknown). Throws owsim::Error naming the file
// for any other layout or a short file.
[[nodiscard]] ReportPoints read_report_points_ply(const std::filesystem::path& path);

// points.las as owsim writes it (LAS 1.4, point format 6, UTM/UPS with the WKT VLR,
// io/points/las_writer.hpp): positions through the zone's inverse projection into the local frame
// of `origin`; without an origin, easting/northing/height minus the file's offsets (a frame of
// the file's own, not the scenario's). Classes from the ASPRS codes owsim writes (2, 5, 6, 7 noise,
// 14, 15, 18; others unknown); no range, frame or fiber. Throws owsim::Error naming the file for
// another format, a missing or unknown coordinate system, or a short file.
[[nodiscard]] ReportPoints read_report_points_las(const std::filesystem::path& path,
                                                  const std::optional<Geodetic>& origin);

}  // namespace owsim
