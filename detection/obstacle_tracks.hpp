#pragma once
// Tracks of obstacles over frames (DETECTION-SPEC §3): an obstacle of a frame continues the track
// it lies on — the one whose remembered points are nearest to a sample of its points (mean
// distance, with at least half of the sample within 2 m + 1 % of the range of a solid's, or within
// 2 × wire_band_m + 10 % of the distance along the line of a wire's: conductors lie metres apart),
// wires with wires and solids with solids, each track taken once, nearest pairs first — or starts
// a new one with the next id. A track remembers every point it has shown (one per 1 m voxel, at most
// kMaxRememberedPoints): its extent never shrinks when part of it leaves the field or the window.
// Tracks that one obstacle continues at once (pieces of it seen apart before) become one, with the
// oldest id.
// A solid track's class is the rules' verdict on what it has shown (its remembered extent, its
// lowest base, its latest isolation), so a warning's class holds for the size it reports; the
// frame's own class stands only where the remembered shape fits no class.
// It reports in every frame until hold_s has passed without support.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <unordered_set>
#include <vector>

#include "detection/detector_params.hpp"
#include "detection/obstacle_class.hpp"

namespace owsim {

inline constexpr std::size_t kMaxRememberedPoints = 4096;

// One frame's obstacle, as the classifier left it.
struct FrameObstacle {
  ObstacleClass kind = ObstacleClass::none;
  std::vector<Eigen::Vector3d> points;
  double base_u_m = 0.0;  // where its visible height starts: the ground it stands on, or its foot
  double isolation_m = 0.0;  // a solid's: horizontal distance to the nearest other object
};

struct ObstacleTrack {
  std::int64_t id = 0;
  ObstacleClass kind = ObstacleClass::none;
  double last_support_s = 0.0;
  std::uint32_t points_now = 0;  // the points supporting it this frame (0: held)
  double base_u_m = 0.0;         // the lowest base it has shown (FrameObstacle::base_u_m)
  double isolation_m = 0.0;      // its latest obstacle's
  std::vector<Eigen::Vector3d> remembered;
  std::unordered_set<std::uint64_t> voxels;  // of `remembered`
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();  // box
  // The plan extent and plan centre of `remembered`, made again only when it has grown (after
  // each update): what association, the class and the warning read of it.
  PlanExtent extent;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double along_lo_m = 0.0, along_hi_m = 0.0;  // the span of `remembered` along extent.axis from centre
  std::size_t extent_points = 0;  // remembered.size() they are of
};

class ObstacleTracks {
 public:
  explicit ObstacleTracks(const DetectorParams& params) : params_(params) {}

  // Associates the frame's obstacles at `time_s`, seen from `aircraft_enu_m`, starts tracks for
  // the rest and drops those unsupported for longer than hold_s.
  void update(std::span<const FrameObstacle> obstacles, double time_s,
              const Eigen::Vector3d& aircraft_enu_m);
  // The live tracks, by id.
  [[nodiscard]] std::span<const ObstacleTrack> tracks() const { return tracks_; }

 private:
  void support(ObstacleTrack& track, const FrameObstacle& obstacle, double time_s);
  static void remember(ObstacleTrack& track, const Eigen::Vector3d& p);
  static void refresh_extent(ObstacleTrack& track);
  void classify_remembered(ObstacleTrack& track) const;

  DetectorParams params_;
  std::vector<ObstacleTrack> tracks_;
  std::int64_t next_id_ = 1;
};

}  // namespace owsim
