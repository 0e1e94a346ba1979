#pragma once
// The source's obstacle classes and their rules (DETECTION-SPEC §2, source ch. 1), as pure
// functions of what is visible: an obstacle's points, the visible ground beneath them, and how far
// the nearest other object is. Definitions (DETECTION-SPEC §2 Decision): visible height = highest
// point − the visible ground beneath it; length = the extent along the principal horizontal axis
// of the points, width = the extent across it.
//
// One reading of ours (docs/detection.md): the source's POLE rule says "width < 10 m"; a wall seen
// face-on is thin across its principal axis (its depth is hidden) and would pass as a pole, so a
// POLE must be under pole_max_width_m along both horizontal axes.
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string_view>

#include "detection/detector_params.hpp"

namespace owsim {

enum class ObstacleClass : std::uint8_t { none, wire, pole, tree };

// "none", "wire", "pole", "tree": detections.csv's class cell.
[[nodiscard]] std::string_view to_string(ObstacleClass kind);

// A return the detector kept: local ENU position, the visible ground under it (NaN: none seen),
// and its distance from the aircraft when it was added.
struct ObstaclePoint {
  Eigen::Vector3d enu_m = Eigen::Vector3d::Zero();
  double ground_u_m = 0.0;
  double range_m = 0.0;
};

// Horizontal extents of a set of points about their principal horizontal axis (the eigenvector
// of the larger eigenvalue of the plan covariance).
struct PlanExtent {
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();  // unit, plan (east, north)
  double length_m = 0.0;                            // along the axis
  double width_m = 0.0;                             // across it
};
[[nodiscard]] PlanExtent plan_extent(std::span<const Eigen::Vector3d> points);

// The unit eigenvector of the larger eigenvalue of the symmetric matrix [[a, b], [b, c]] (a plan
// covariance), in closed form; east when the matrix has no preferred direction.
[[nodiscard]] Eigen::Vector2d principal_axis(double a, double b, double c);

// What the rules measure of one obstacle.
struct ObstacleShape {
  double length_m = 0.0;
  double width_m = 0.0;
  double height_m = 0.0;          // visible height: top − the ground it stands on (or its foot)
  double clearance_m = 0.0;       // a wire's: median height of its points above the visible ground
  double isolation_m = 0.0;       // horizontal distance to the nearest other object
  double isolated_share = 1.0;    // a wire's: share of its points ≥ wire_isolation_m from others
};

// WIRE: length / width > wire_min_aspect (the shape alone: what makes a line of points a wire
// candidate before its surroundings are looked at).
[[nodiscard]] bool wire_shaped(double length_m, double width_m, const DetectorParams& params);
// The whole WIRE rule: wire_shaped, isolated from other objects (by wire_isolated_share of its
// points), and ≥ wire_min_clearance_m above the visible ground.
[[nodiscard]] bool wire_rule(const ObstacleShape& shape, const DetectorParams& params);
// POLE, else TREE, else none, for an obstacle that is not a wire.
[[nodiscard]] ObstacleClass solid_class(const ObstacleShape& shape, const DetectorParams& params);

}  // namespace owsim
