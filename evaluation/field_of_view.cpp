#include "evaluation/field_of_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace owsim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
};

// A union of at most four disjoint closed intervals of the line parameter t.
class IntervalSet {
 public:
  static IntervalSet all() { return IntervalSet({-kInf, kInf}); }
  static IntervalSet none() { return {}; }
  IntervalSet() = default;
  explicit IntervalSet(Interval interval) { add(interval); }

  void add(Interval interval) {
    if (interval.lo <= interval.hi && count_ < items_.size()) items_[count_++] = interval;
  }
  [[nodiscard]] IntervalSet intersected(const IntervalSet& other) const {
    IntervalSet out;
    for (std::size_t i = 0; i < count_; ++i) {
      for (std::size_t j = 0; j < other.count_; ++j) {
        out.add({std::max(items_[i].lo, other.items_[j].lo),
                 std::min(items_[i].hi, other.items_[j].hi)});
      }
    }
    return out;
  }
  // The smallest interval holding every piece (empty stays empty).
  [[nodiscard]] IntervalSet hull() const {
    if (count_ == 0) return {};
    Interval whole = items_[0];
    for (std::size_t i = 1; i < count_; ++i) {
      whole.lo = std::min(whole.lo, items_[i].lo);
      whole.hi = std::max(whole.hi, items_[i].hi);
    }
    return IntervalSet(whole);
  }
  // ℝ without the interior of the one interval this set holds (empty: ℝ).
  [[nodiscard]] IntervalSet complement_of_interior() const {
    if (count_ == 0) return all();
    IntervalSet out;
    out.add({-kInf, items_[0].lo});
    out.add({items_[0].hi, kInf});
    return out;
  }
  [[nodiscard]] std::size_t size() const { return count_; }
  [[nodiscard]] const Interval& operator[](std::size_t i) const { return items_[i]; }

 private:
  std::array<Interval, 4> items_{};
  std::size_t count_ = 0;
};

// {t : g0 + g1·t ≥ 0}
IntervalSet linear_at_least_zero(double g0, double g1) {
  if (g1 == 0.0) return g0 >= 0.0 ? IntervalSet::all() : IntervalSet::none();
  const double root = -g0 / g1;
  return g1 > 0.0 ? IntervalSet({root, kInf}) : IntervalSet({-kInf, root});
}

// {t : A·t² + B·t + C ≥ 0}
IntervalSet quadratic_at_least_zero(double a, double b, double c) {
  if (a == 0.0) return linear_at_least_zero(c, b);
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0) return a > 0.0 ? IntervalSet::all() : IntervalSet::none();
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  double r1 = q / a;
  double r2 = q != 0.0 ? c / q : r1;
  if (r1 > r2) std::swap(r1, r2);
  if (a < 0.0) return IntervalSet({r1, r2});
  IntervalSet out;
  out.add({-kInf, r1});
  out.add({r2, kInf});
  return out;
}

// {t : u·v(t) ≥ s·|v(t)|}, v(t) = p + t·d, u a unit axis, 0 ≤ s < 1: a convex cone, one interval.
IntervalSet inside_cone(const Eigen::Vector3d& u, double s, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& d) {
  const double g0 = u.dot(p);
  const double g1 = u.dot(d);
  const double s2 = s * s;
  const IntervalSet quadric =
      quadratic_at_least_zero(g1 * g1 - s2 * d.squaredNorm(), 2.0 * (g0 * g1 - s2 * p.dot(d)),
                              g0 * g0 - s2 * p.squaredNorm());
  return quadric.intersected(linear_at_least_zero(g0, g1)).hull();
}

// {t : a(t) ≥ s·|v(t)|}, s = sin α: α ≥ the bound (a the ARC a component, SRC y).
IntervalSet alpha_at_least(double s, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  if (s >= 0.0) return inside_cone(Eigen::Vector3d::UnitY(), s, p, d);
  return inside_cone(-Eigen::Vector3d::UnitY(), -s, p, d).complement_of_interior();
}

// {t : a(t) ≤ s·|v(t)|}: α ≤ the bound.
IntervalSet alpha_at_most(double s, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  if (s < 0.0) return inside_cone(-Eigen::Vector3d::UnitY(), -s, p, d);
  return inside_cone(Eigen::Vector3d::UnitY(), s, p, d).complement_of_interior();
}

// β ≥ β₁: b·cos β₁ − c·sin β₁ ≥ 0, with (a, b, c) = (y, z, x) in SRC axes.
IntervalSet beta_at_least(double sin_b, double cos_b, const Eigen::Vector3d& p,
                          const Eigen::Vector3d& d) {
  return linear_at_least_zero(p.z() * cos_b - p.x() * sin_b, d.z() * cos_b - d.x() * sin_b);
}

// β ≤ β₂: c·sin β₂ − b·cos β₂ ≥ 0.
IntervalSet beta_at_most(double sin_b, double cos_b, const Eigen::Vector3d& p,
                         const Eigen::Vector3d& d) {
  return linear_at_least_zero(p.x() * sin_b - p.z() * cos_b, d.x() * sin_b - d.z() * cos_b);
}

// |v(t)| ≤ R
IntervalSet within_range(double range_m, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  return quadratic_at_least_zero(-d.squaredNorm(), -2.0 * p.dot(d),
                                 range_m * range_m - p.squaredNorm());
}

}  // namespace

FieldAngles field_angles(const Eigen::Vector3d& v_src) {
  // α = asin(a / |v|) = atan(a / √(b² + c²)) and β = atan2(b, c) = atan(b / c) (± 180° behind),
  // each as the arctangent of one quotient (within an ulp or two of asin and atan2): glibc's asin
  // and atan2 read tables that a frame's ground truth finds out of cache in a flight
  // (bench_frame_truth BM_FrameTruth/1, corridor frame, 64 MB written between frames: median of
  // 8 interleaved runs 96 → 90 µs).
  const double x = v_src.x(), y = v_src.y(), z = v_src.z();
  if (!(x * x + y * y + z * z > 0.0)) return {};
  const double across = std::sqrt(x * x + z * z);
  const double alpha = std::atan(y / across);  // across = 0: ±90°
  double beta = 0.0;
  if (x > 0.0) {
    beta = std::atan(z / x);
  } else if (x < 0.0) {
    beta = std::atan(z / x) + (std::signbit(z) ? -std::numbers::pi : std::numbers::pi);
  } else {
    beta = std::atan2(z, x);  // on the b axis, or the origin's signed zeros
  }
  return {alpha / kRadPerDeg, beta / kRadPerDeg};
}

FieldOfView::FieldOfView(const ScanField& field)
    : field_(field),
      sin_alpha_min_(std::sin(field.alpha_min_deg * kRadPerDeg)),
      sin_alpha_max_(std::sin(field.alpha_max_deg * kRadPerDeg)),
      sin_beta_min_(std::sin(field.beta_min_deg * kRadPerDeg)),
      cos_beta_min_(std::cos(field.beta_min_deg * kRadPerDeg)),
      sin_beta_max_(std::sin(field.beta_max_deg * kRadPerDeg)),
      cos_beta_max_(std::cos(field.beta_max_deg * kRadPerDeg)) {}

bool FieldOfView::contains(const Eigen::Vector3d& v_src) const {
  // The bounds as nearest_inside takes them: the β planes, a against |v|·sin α, the range ball.
  const double length = v_src.norm();
  return length <= field_.range_max_m &&
         v_src.z() * cos_beta_min_ - v_src.x() * sin_beta_min_ >= 0.0 &&
         v_src.x() * sin_beta_max_ - v_src.z() * cos_beta_max_ >= 0.0 &&
         v_src.y() >= sin_alpha_min_ * length && v_src.y() <= sin_alpha_max_ * length;
}

double nearest_on_segment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  const Eigen::Vector3d d = p1 - p0;
  const double length2 = d.squaredNorm();
  if (!(length2 > 0.0)) return 0.0;
  return std::clamp(-p0.dot(d) / length2, 0.0, 1.0);
}

bool FieldOfView::may_hold_sphere(const Eigen::Vector3d& centre_src, double radius_m) const {
  const double distance = centre_src.norm();
  if (distance - radius_m > field_.range_max_m) return false;
  if (distance <= radius_m) return true;  // around the sensor
  // Wholly beyond one of the β planes (b·cos β₁ − c·sin β₁ ≥ 0, c·sin β₂ − b·cos β₂ ≥ 0; unit
  // normals).
  if (centre_src.z() * cos_beta_min_ - centre_src.x() * sin_beta_min_ < -radius_m) return false;
  if (centre_src.x() * sin_beta_max_ - centre_src.z() * cos_beta_max_ < -radius_m) return false;
  // Wholly above or below the α bounds: the centre's α more than the angular radius s away. With
  // sines and cosines of α ± s (α ∈ [−90°, 90°], s ∈ [0°, 90°]): α + s ≥ α₁ holds when α + s ≥ 90°
  // (its cosine ≤ 0), else when its sine ≥ sin α₁; α − s ≤ α₂ likewise. No inverse sines.
  const double sin_s = radius_m / distance;
  const double cos_s = std::sqrt(std::max(0.0, 1.0 - sin_s * sin_s));
  const double sin_a = std::clamp(centre_src.y() / distance, -1.0, 1.0);
  const double cos_a =
      std::sqrt(centre_src.x() * centre_src.x() + centre_src.z() * centre_src.z()) / distance;
  const bool above_lowest = cos_a * cos_s - sin_a * sin_s <= 0.0 ||
                            sin_a * cos_s + cos_a * sin_s >= sin_alpha_min_;
  const bool below_highest = cos_a * cos_s + sin_a * sin_s <= 0.0 ||
                             sin_a * cos_s - cos_a * sin_s <= sin_alpha_max_;
  return above_lowest && below_highest;
}

bool FieldOfView::wholly_outside(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) const {
  // Beyond one β plane (a half-space: convex, so both ends beyond it holds the whole segment).
  const auto below_beta_min = [&](const Eigen::Vector3d& v) {
    return v.z() * cos_beta_min_ - v.x() * sin_beta_min_ < 0.0;
  };
  const auto above_beta_max = [&](const Eigen::Vector3d& v) {
    return v.x() * sin_beta_max_ - v.z() * cos_beta_max_ < 0.0;
  };
  if (below_beta_min(p0) && below_beta_min(p1)) return true;
  if (above_beta_max(p0) && above_beta_max(p1)) return true;
  // Below a negative lowest α (a ≤ |v|·sin α₁ < 0: the inside of a convex cone about −a), or
  // above a positive highest α; squared, so no square root.
  const auto below_alpha_min = [&](const Eigen::Vector3d& v) {
    return v.y() < 0.0 && v.y() * v.y() > sin_alpha_min_ * sin_alpha_min_ * v.squaredNorm();
  };
  const auto above_alpha_max = [&](const Eigen::Vector3d& v) {
    return v.y() > 0.0 && v.y() * v.y() > sin_alpha_max_ * sin_alpha_max_ * v.squaredNorm();
  };
  if (sin_alpha_min_ < 0.0 && below_alpha_min(p0) && below_alpha_min(p1)) return true;
  return sin_alpha_max_ > 0.0 && above_alpha_max(p0) && above_alpha_max(p1);
}

std::optional<double> FieldOfView::nearest_inside(const Eigen::Vector3d& p0,
                                                  const Eigen::Vector3d& p1) const {
  if (wholly_outside(p0, p1)) return std::nullopt;
  const Eigen::Vector3d d = p1 - p0;
  IntervalSet inside = IntervalSet({0.0, 1.0});
  inside = inside.intersected(beta_at_least(sin_beta_min_, cos_beta_min_, p0, d));
  inside = inside.intersected(beta_at_most(sin_beta_max_, cos_beta_max_, p0, d));
  if (inside.size() == 0) return std::nullopt;
  inside = inside.intersected(within_range(field_.range_max_m, p0, d));
  if (inside.size() == 0) return std::nullopt;
  // The β planes and the range ball leave one interval, on which |v(t)|² is least at the clamped
  // free minimiser: when that point meets both α bounds it is the answer, and the cones are not
  // needed (the common case for a segment in view).
  const double length2 = d.squaredNorm();
  const double free_t = length2 > 0.0 ? -p0.dot(d) / length2 : 0.0;
  if (inside.size() == 1) {
    const double t = std::clamp(free_t, inside[0].lo, inside[0].hi);
    const Eigen::Vector3d v = p0 + t * d;
    const double length = v.norm();
    if (v.y() >= sin_alpha_min_ * length && v.y() <= sin_alpha_max_ * length) return t;
  }
  inside = inside.intersected(alpha_at_least(sin_alpha_min_, p0, d));
  inside = inside.intersected(alpha_at_most(sin_alpha_max_, p0, d));
  if (inside.size() == 0) return std::nullopt;
  double best_t = 0.0;
  double best = kInf;
  for (std::size_t i = 0; i < inside.size(); ++i) {
    const double t = std::clamp(free_t, inside[i].lo, inside[i].hi);
    const double distance2 = (p0 + t * d).squaredNorm();
    if (distance2 < best) {
      best = distance2;
      best_t = t;
    }
  }
  return best_t;
}

}  // namespace owsim
