#include "detection/obstacle_class.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace owsim {

std::string_view to_string(ObstacleClass kind) {
  switch (kind) {
    case ObstacleClass::wire:
      return "wire";
    case ObstacleClass::pole:
      return "pole";
    case ObstacleClass::tree:
      return "tree";
    case ObstacleClass::none:
      break;
  }
  return "none";
}

Eigen::Vector2d principal_axis(double a, double b, double c) {
  // The larger eigenvalue of [[a, b], [b, c]] and its eigenvector, from the row that is the
  // better conditioned of the two (λ − c ≥ λ − a when a ≥ c).
  const double half_difference = 0.5 * (a - c);
  const double lambda = 0.5 * (a + c) + std::hypot(half_difference, b);
  Eigen::Vector2d axis = a >= c ? Eigen::Vector2d(lambda - c, b) : Eigen::Vector2d(b, lambda - a);
  const double norm = axis.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) return Eigen::Vector2d::UnitX();
  return axis / norm;
}

PlanExtent plan_extent(std::span<const Eigen::Vector3d> points) {
  PlanExtent out;
  if (points.empty()) return out;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p.head<2>();
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector2d d = p.head<2>() - mean;
    covariance += d * d.transpose();
  }
  Eigen::Vector2d axis = principal_axis(covariance(0, 0), covariance(0, 1), covariance(1, 1));
  // One orientation whatever the solver returns: east-pointing, or north-pointing when due north.
  if (axis.x() < 0.0 || (axis.x() == 0.0 && axis.y() < 0.0)) axis = -axis;
  const Eigen::Vector2d across(-axis.y(), axis.x());
  double along_lo = std::numeric_limits<double>::infinity(), along_hi = -along_lo;
  double across_lo = along_lo, across_hi = -along_lo;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector2d d = p.head<2>() - mean;
    const double s = d.dot(axis), t = d.dot(across);
    along_lo = std::min(along_lo, s);
    along_hi = std::max(along_hi, s);
    across_lo = std::min(across_lo, t);
    across_hi = std::max(across_hi, t);
  }
  out.axis = axis;
  out.length_m = along_hi - along_lo;
  out.width_m = across_hi - across_lo;
  return out;
}

bool wire_shaped(double length_m, double width_m, const DetectorParams& params) {
  // A line of points has no width below what the points resolve: 5 cm, a wire's own scale.
  return length_m > params.wire_min_aspect * std::max(width_m, 0.05);
}

bool wire_rule(const ObstacleShape& shape, const DetectorParams& params) {
  return wire_shaped(shape.length_m, shape.width_m, params) &&
         shape.isolated_share >= params.wire_isolated_share &&
         shape.clearance_m >= params.wire_min_clearance_m;
}

ObstacleClass solid_class(const ObstacleShape& shape, const DetectorParams& params) {
  if (shape.height_m > params.pole_min_height_m &&
      shape.width_m < params.pole_max_aspect * shape.height_m &&
      shape.width_m < params.pole_max_width_m && shape.length_m < params.pole_max_width_m) {
    return ObstacleClass::pole;
  }
  if (shape.height_m > params.tree_min_height_m && shape.width_m <= params.tree_max_width_m &&
      shape.isolation_m >= params.tree_isolation_widths * shape.width_m) {
    return ObstacleClass::tree;
  }
  return ObstacleClass::none;
}

}  // namespace owsim
