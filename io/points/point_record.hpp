#pragma once
// One detected return as the point writers consume it (INTERFACE.md "`owsim run` outputs":
// points.csv, points.las, points.ply), and the interface every point sink implements.
//
// Filled by the flight pipeline (simulated returns) or by the decoder (words + trajectory). A
// decoded return knows no class, object, energy or incidence: `surface` is then std::nullopt,
// `object_index` kNoObject and energy_rel / incidence_deg NaN; every writer has a documented
// spelling for "unknown". Sinks are streaming: created once (may allocate, may throw), then
// given the points frame by frame in firing order, then finish() makes the file appear complete.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"

namespace owsim {

struct PointRecord {
  std::int64_t frame = 0;
  int pulse = 0;                                    // index within the frame, 0-based
  int line = 0;                                     // scan line within the frame
  int fiber = 0;                                    // 1..127
  int return_number = 1;                            // 1 or 2 (first or second return of the pulse)
  int number_of_returns = 1;                        // returns the pulse registered, 1 or 2
  double time_s = 0;                                // pulse time on the trajectory's clock
  double range_m = 0;                               // simulated range, after noise
  std::uint16_t counter = 0;                        // the range counter the word holds
  Eigen::Vector3d enu_m = Eigen::Vector3d::Zero();  // local East-North-Up from the scenario origin
  Geodetic geodetic;                                // the same point on WGS-84
  // The same in the UTM/UPS grid points.las uses (easting, northing), when placed with the point
  // (frame_points, geometry/geodesy_cells.hpp); NaN: the LAS writer computes it.
  Eigen::Vector2d grid_m = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  std::optional<SurfaceClass> surface;     // std::nullopt: unknown
  std::uint32_t object_index = kNoObject;  // into the writer's object-id table; kNoObject: none
                                           // (geometry/scene.hpp: a false return, or unknown)
  double energy_rel = std::numeric_limits<double>::quiet_NaN();     // ξ_rx/ξ_tx; NaN: unknown
  double incidence_deg = std::numeric_limits<double>::quiet_NaN();  // NaN: unknown
  double scan_angle_deg = 0;  // mirror angle β of the pulse (LAS scan angle)
};

// A point file being written. write() may be called any number of times (a frame's returns at
// a time); finish() flushes, completes the header and renames the file to its final name, after
// which nothing may be written. Destroying a sink without finish() leaves no file behind.
class PointSink {
 public:
  virtual ~PointSink() = default;
  virtual void write(std::span<const PointRecord> points) = 0;
  virtual void finish() = 0;
  [[nodiscard]] virtual std::uint64_t points_written() const = 0;
};

}  // namespace owsim
