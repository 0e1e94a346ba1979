#pragma once
// The reference obstacle detector (DETECTION-SPEC): a frame's returns in, the pilot's warnings out.
// It reads only what the real processor has — the returns' positions in the local ENU frame, as
// the recorded counters and the navigation pose place them, and the aircraft's navigation position
// — never a return's class, object, energy or incidence (the truth it is scored against).
//
// Each frame (DETECTION-SPEC §2–§3):
// 1. Its returns within max_range_m lower the ground map (detection/ground_map.hpp); those at least
//    min_height_m above the visible ground join the window of the last window_s of frames.
// 2. Wire candidates among the window's points (detection/wire_lines.hpp): WIRE when isolated
//    (wire_isolated_share of their points ≥ wire_isolation_m from any other obstacle's, in plan)
//    and their median height above the visible ground is ≥ wire_min_clearance_m.
// 3. The other points in clusters (detection/obstacle_clusters.hpp) of at least min_points: POLE,
//    TREE or none by the source's rules (detection/obstacle_class.hpp).
// 4. WIREs, POLEs and TREEs continue or start tracks (detection/obstacle_tracks.hpp); every live
//    track is a warning of the frame, at its remembered point nearest to the aircraft, with the
//    extent it has shown.
// Set up once (validates, allocates); add_frame is then deterministic — the same frames give the
// same warnings bit for bit, whatever thread calls it — and allocates only while buffers grow.
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "detection/detector_params.hpp"
#include "detection/ground_map.hpp"
#include "detection/obstacle_class.hpp"
#include "detection/obstacle_clusters.hpp"
#include "detection/obstacle_tracks.hpp"
#include "detection/wire_lines.hpp"

namespace owsim {

// What the detector reads of one frame.
struct DetectorFrame {
  std::int64_t frame = 0;
  double time_s = 0.0;  // of the frame's first pulse
  Eigen::Vector3d aircraft_enu_m = Eigen::Vector3d::Zero();  // navigation position at time_s
  std::span<const Eigen::Vector3d> returns_enu_m;            // the frame's returns
};

// One warning: a track's report in a frame (detections.csv's row, DETECTION-SPEC §5).
struct ObstacleWarning {
  std::int64_t frame = 0;
  double time_s = 0.0;
  std::int64_t track = 0;
  ObstacleClass kind = ObstacleClass::none;
  Eigen::Vector3d nearest_enu_m = Eigen::Vector3d::Zero();  // nearest point to the aircraft
  double range_m = 0.0;                                     // its distance from the aircraft
  double length_m = 0.0;
  double width_m = 0.0;
  double height_m = 0.0;  // visible height
  std::uint32_t points = 0;  // supporting it in this frame's window (0: held without support)
};

class ObstacleDetector {
 public:
  // Throws owsim::Error naming the first bad parameter. `frame_period_s` (> 0) sets how many
  // frames the window holds: max(1, ⌊window_s / frame_period_s⌋), as `owsim pd` counts windows.
  ObstacleDetector(const DetectorParams& params, double frame_period_s);

  // The warnings of the next frame (frames in time order), by track id; valid until the next call.
  std::span<const ObstacleWarning> add_frame(const DetectorFrame& frame);

  [[nodiscard]] const DetectorParams& params() const { return params_; }
  [[nodiscard]] std::span<const ObstacleTrack> tracks() const { return tracks_.tracks(); }

 private:
  void classify(const Eigen::Vector3d& aircraft);

  DetectorParams params_;
  std::size_t window_frames_;
  GroundMap ground_;
  std::deque<std::vector<ObstaclePoint>> window_;
  ObstacleTracks tracks_;
  // Per-frame buffers.
  struct NearbyReturn {
    GroundMap::Place cell;
    double range_m;
    std::uint32_t index;  // in the frame's returns
  };
  std::vector<NearbyReturn> nearby_;
  std::vector<ObstaclePoint> points_;
  WireSearchScratch wire_scratch_;
  ClusterScratch cluster_scratch_;
  std::vector<WireCandidate> wires_;
  std::vector<PointCluster> all_clusters_;  // the window's, wires' points included
  std::vector<PointCluster> clusters_;      // without the wires' points
  std::vector<FrameObstacle> obstacles_;
  std::vector<ObstacleWarning> warnings_;
};

}  // namespace owsim
