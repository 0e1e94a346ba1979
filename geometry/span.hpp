#pragma once
// A power-line span in 3D (SENSOR-SPEC §6): the conductors between two supports, each its own
// catenary (geometry/catenary.hpp) sampled into a polyline within 1 mm of the curve, and the
// support poles as cylinders.
//
// Geometry, in local ENU metres: the span runs horizontally from `from_en` to `to_en`. Conductor
// n (offset n − 1 of `offsets`, geometry/conductor_layout.hpp) hangs in the vertical plane
// through from → to shifted by its lateral offset to the right. Its attachment heights are
//   H1' = terrain(from) + support_height_1_m + vertical,  H2' = terrain(to) + support_height_2_m
//   + vertical,
// with the terrain read under the span's support points (the tower centre: a rigid crossarm
// holds all conductors of one tower at the same ground reference), and its lowest point is
//   S' = min(terrain(from), terrain(to)) + lowest_point_m + vertical,
// i.e. every conductor has the sag of the span's reference wire and S is measured from the
// lower support's ground. Each support pole is a cylinder from the terrain under its support up
// to support height + max(0, highest vertical offset), so the conductors end at the pole tops.
// Ids: conductors "<id>/<n>" (INTERFACE.md), poles "<id>/pole-1" (at from) and "<id>/pole-2".
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/conductor_layout.hpp"
#include "geometry/scene.hpp"
#include "geometry/terrain.hpp"

namespace owsim {

inline constexpr double kWireChordErrorM = 0.001;  // DESIGN.md: polyline within 1 mm of the curve

struct SpanSpec {
  std::string id;
  Eigen::Vector2d from_en = Eigen::Vector2d::Zero();  // support 1, east/north metres
  Eigen::Vector2d to_en = Eigen::Vector2d::Zero();    // support 2
  double support_height_1_m = 30.0;                   // H1 above the terrain at `from`
  double support_height_2_m = 30.0;                   // H2 above the terrain at `to`
  double lowest_point_m = 20.0;                       // S above the lower support's terrain
  std::vector<ConductorOffset> offsets = {{0.0, 0.0}};
  double conductor_diameter_m = 0.020;  // SENSOR-SPEC §6: 16–21 mm
  double conductor_reflectivity = 0.4;  // SENSOR-SPEC §6 nominal
  bool support_poles = true;
  double pole_diameter_m = 0.5;
  double pole_reflectivity = 0.3;
};

struct SpanObjects {
  std::vector<Conductor> conductors;  // in layout order
  std::vector<Cylinder> poles;        // empty unless support_poles
};

// Builds the span's conductors and poles on the terrain. Throws owsim::Error
// "<where>.<key>: <problem>" (or "<key>: …" when `where` is empty), keys as in the scenario
// (INTERFACE.md): id (empty), from / to (not finite, equal, or off the terrain grid),
// support_heights_m (not finite or ≤ 0), lowest_point_m (not finite, < 0, above a support, or a
// conductor whose lowest point would lie below the terrain), layout (empty or non-finite
// offsets), conductor.diameter_mm (not > 0), conductor.reflectivity and supports.reflectivity
// (outside 0..1), supports.diameter_m (not > 0).
[[nodiscard]] SpanObjects build_span(const SpanSpec& spec, const Terrain& terrain,
                                     std::string_view where = {});

}  // namespace owsim
