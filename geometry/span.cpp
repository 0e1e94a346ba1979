#include "geometry/span.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geometry/catenary.hpp"
#include "geometry/error.hpp"
#include "geometry/number_text.hpp"

namespace owsim {
namespace {

class SpanChecker {
 public:
  explicit SpanChecker(std::string_view where) : where_(where) {}

  [[nodiscard]] std::string key(std::string_view name) const {
    if (where_.empty()) return std::string(name);
    std::string full(where_);
    full += '.';
    full += name;
    return full;
  }
  [[noreturn]] void fail(std::string_view name, const std::string& problem) const {
    throw input_error(key(name), problem);
  }
  void positive(std::string_view name, double value, double shown_scale = 1.0,
                std::string_view unit = "m") const {
    if (!(std::isfinite(value) && value > 0.0)) {
      fail(name, "must be a finite number > 0, got " + number_text(value * shown_scale) + " " +
                     std::string(unit));
    }
  }
  void fraction(std::string_view name, double value) const {
    if (!(std::isfinite(value) && value >= 0.0 && value <= 1.0)) {
      fail(name, "must be between 0 and 1, got " + number_text(value));
    }
  }

 private:
  std::string_view where_;
};

void check_span(const SpanSpec& spec, const SpanChecker& check) {
  if (spec.id.empty()) check.fail("id", "a span needs a non-empty id");
  if (!spec.from_en.allFinite()) check.fail("from", "the position must be finite");
  if (!spec.to_en.allFinite()) check.fail("to", "the position must be finite");
  if ((spec.to_en - spec.from_en).norm() == 0.0) {
    check.fail("to", "the two supports stand at the same place");
  }
  check.positive("support_heights_m", spec.support_height_1_m);
  check.positive("support_heights_m", spec.support_height_2_m);
  const double s = spec.lowest_point_m;
  if (!(std::isfinite(s) && s >= 0.0)) {
    check.fail("lowest_point_m", "must be a finite number ≥ 0, got " + number_text(s) + " m");
  }
  if (s > spec.support_height_1_m || s > spec.support_height_2_m) {
    check.fail("lowest_point_m", number_text(s) + " m is above a support (support_heights_m " +
                                     number_text(spec.support_height_1_m) + ", " +
                                     number_text(spec.support_height_2_m) + ")");
  }
  if (spec.offsets.empty()) check.fail("layout", "a span needs at least one conductor");
  for (std::size_t i = 0; i < spec.offsets.size(); ++i) {
    const ConductorOffset& offset = spec.offsets[i];
    if (!(std::isfinite(offset.lateral_m) && std::isfinite(offset.vertical_m))) {
      check.fail("layout", "conductor " + std::to_string(i + 1) + " has a non-finite offset");
    }
    if (s + offset.vertical_m < 0.0) {
      check.fail("lowest_point_m",
                 "conductor " + std::to_string(i + 1) + " hangs " +
                     number_text(-offset.vertical_m) +
                     " m below the support height, so its lowest point would be " +
                     number_text(s + offset.vertical_m) + " m, under the terrain");
    }
  }
  check.positive("conductor.diameter_mm", spec.conductor_diameter_m, 1000.0, "mm");
  check.fraction("conductor.reflectivity", spec.conductor_reflectivity);
  if (spec.support_poles) {
    check.positive("supports.diameter_m", spec.pole_diameter_m);
    check.fraction("supports.reflectivity", spec.pole_reflectivity);
  }
}

double terrain_under(const Terrain& terrain, const Eigen::Vector2d& at, std::string_view name,
                     const SpanChecker& check) {
  try {
    return terrain.height_at(at.x(), at.y());
  } catch (const Error& error) {
    check.fail(name, error.what());
  }
}

}  // namespace

SpanObjects build_span(const SpanSpec& spec, const Terrain& terrain, std::string_view where) {
  const SpanChecker check(where);
  check_span(spec, check);

  const double ground_1 = terrain_under(terrain, spec.from_en, "from", check);
  const double ground_2 = terrain_under(terrain, spec.to_en, "to", check);
  const double ground_low = std::min(ground_1, ground_2);
  const Eigen::Vector2d along = spec.to_en - spec.from_en;
  const double span_m = along.norm();
  const Eigen::Vector2d forward = along / span_m;
  const Eigen::Vector2d right(forward.y(), -forward.x());  // looking from → to

  SpanObjects objects;
  objects.conductors.reserve(spec.offsets.size());
  for (std::size_t i = 0; i < spec.offsets.size(); ++i) {
    const ConductorOffset& offset = spec.offsets[i];
    const CatenaryProfile profile{span_m, ground_1 + spec.support_height_1_m + offset.vertical_m,
                                  ground_2 + spec.support_height_2_m + offset.vertical_m,
                                  ground_low + spec.lowest_point_m + offset.vertical_m};
    Catenary catenary = [&] {
      try {
        return Catenary::solve(profile);
      } catch (const Error& error) {
        check.fail("lowest_point_m", "conductor " + std::to_string(i + 1) + ": " + error.what());
      }
    }();
    const Eigen::Vector2d start = spec.from_en + offset.lateral_m * right;
    const Eigen::Vector2d end = spec.to_en + offset.lateral_m * right;
    const std::vector<double> xs = catenary.sample_x(kWireChordErrorM);

    Conductor conductor;
    conductor.id = conductor_id(spec.id, static_cast<int>(i + 1));
    conductor.radius_m = 0.5 * spec.conductor_diameter_m;
    conductor.reflectivity = spec.conductor_reflectivity;
    conductor.points_enu_m.reserve(xs.size());
    for (double x : xs) {
      const Eigen::Vector2d en = start + x * forward;
      conductor.points_enu_m.emplace_back(en.x(), en.y(), catenary.height_at(x));
    }
    // Pin the ends to the attachment points exactly.
    conductor.points_enu_m.front() = Eigen::Vector3d(start.x(), start.y(), profile.support_1_m);
    conductor.points_enu_m.back() = Eigen::Vector3d(end.x(), end.y(), profile.support_2_m);
    objects.conductors.push_back(std::move(conductor));
  }

  if (spec.support_poles) {
    double highest = 0.0;
    for (const ConductorOffset& offset : spec.offsets)
      highest = std::max(highest, offset.vertical_m);
    const auto pole = [&](int n, const Eigen::Vector2d& at, double ground, double height) {
      return Cylinder{spec.id + "/pole-" + std::to_string(n),
                      SurfaceClass::pole,
                      Eigen::Vector3d(at.x(), at.y(), ground),
                      0.5 * spec.pole_diameter_m,
                      height + highest,
                      spec.pole_reflectivity};
    };
    objects.poles.push_back(pole(1, spec.from_en, ground_1, spec.support_height_1_m));
    objects.poles.push_back(pole(2, spec.to_en, ground_2, spec.support_height_2_m));
  }
  return objects;
}

}  // namespace owsim
