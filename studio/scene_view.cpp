#include "studio/scene_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "evaluation/frame_truth.hpp"
#include "geometry/error.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim::studio {
namespace {

using nlohmann::json;

// [lat, lon] of a local ENU position, to the centimetre.
json lat_lon(const Geodetic& point) {
  const auto round = [](double deg) { return std::round(deg * 1e7) / 1e7; };
  return json::array({round(point.lat_deg), round(point.lon_deg)});
}
json lat_lon(const LocalFrame& frame, const Eigen::Vector3d& enu_m) {
  return lat_lon(frame.geodetic_from_enu(enu_m));
}

// The ground's height under (e, n), or null where the terrain has none (off a DEM).
json ground_at(const Terrain& terrain, double e_m, double n_m) {
  try {
    return terrain.height_at(e_m, n_m);
  } catch (const Error&) {
    return nullptr;
  }
}

// The WGS-84 outline ([lat, lon] corners, counter-clockwise from south-west) of the east/north
// box e × n: a mesh's or fog box's footprint, the forest's area.
json box_outline(const LocalFrame& frame, const Eigen::Vector2d& e, const Eigen::Vector2d& n) {
  return json::array({lat_lon(frame, {e.x(), n.x(), 0.0}), lat_lon(frame, {e.y(), n.x(), 0.0}),
                      lat_lon(frame, {e.y(), n.y(), 0.0}), lat_lon(frame, {e.x(), n.y(), 0.0})});
}

// About `count` of a polyline's vertices, evenly strided, the last one always: a long span has
// thousands, the map and the cross-section need a few dozen.
template <typename Visit>
void for_sampled_vertices(const std::vector<Eigen::Vector3d>& points, std::size_t count,
                          const Visit& visit) {
  const std::size_t stride = std::max<std::size_t>(1, points.size() / count);
  for (std::size_t k = 0; k < points.size(); k += stride) visit(points[k]);
  visit(points.back());
}

json track_view(const FlightSetup& setup, double step_s) {
  const Trajectory& trajectory = setup.trajectory;
  const LocalFrame& frame = setup.local_frame;
  const Scenario& scenario = setup.scenario;
  // The field's horizontal fan, frame 0's sweep at α = 0, out to the counter's timeout range.
  const ScanField field = frame_field(scenario.scan, frame_sweep(scenario.scan, scenario.seed, 0));
  json t = json::array(), points = json::array(), h = json::array(), agl = json::array(),
       speed = json::array(), heading = json::array(), fans = json::array();
  const double start = trajectory.start_s();
  const double end = trajectory.end_s();
  const auto samples = static_cast<std::int64_t>(std::floor((end - start) / step_s)) + 1;
  for (std::int64_t k = 0; k < samples; ++k) {
    const double time = std::min(end, start + static_cast<double>(k) * step_s);
    const Pose pose = trajectory.pose_at(time);
    const Eigen::Vector3d& at = pose.position_enu_m;
    const double before = std::max(start, time - 0.1), after = std::min(end, time + 0.1);
    const double ground_speed =
        after > before
            ? (trajectory.pose_at(after).position_enu_m - trajectory.pose_at(before).position_enu_m)
                      .norm() /
                  (after - before)
            : 0.0;
    t.push_back(std::round(time * 1e3) / 1e3);
    const Geodetic geodetic = frame.geodetic_from_enu(at);
    points.push_back(lat_lon(geodetic));
    h.push_back(std::round(geodetic.h_m * 100) / 100);
    const json ground = ground_at(setup.scene.terrain, at.x(), at.y());
    agl.push_back(ground.is_null() ? json(nullptr)
                                   : json(std::round((at.z() - ground.get<double>()) * 100) / 100));
    speed.push_back(std::round(ground_speed * 100) / 100);
    heading.push_back(std::round(pose.attitude.heading_deg * 10) / 10);
    const SensorPlacement placement = sensor_placement(pose, scenario.mount, scenario.scan.model);
    json fan = json::array({lat_lon(frame, placement.origin_enu_m)});
    for (int edge = 0; edge <= 4; ++edge) {
      const double beta = field.beta_min_deg + (field.beta_max_deg - field.beta_min_deg) * edge / 4;
      const Eigen::Vector3d ray_src = src_from_arc(arc_unit_ray(0.0, beta));
      fan.push_back(lat_lon(
          frame, placement.origin_enu_m + field.range_max_m * (placement.enu_from_src * ray_src)));
    }
    fans.push_back(std::move(fan));
  }
  return {{"t", t},         {"points", points},
          {"h", h},         {"agl", agl},
          {"speed", speed}, {"heading", heading},
          {"fov", fans},    {"start_s", start},
          {"end_s", end},   {"range_m", field.range_max_m}};
}

json objects_view(const FlightSetup& setup) {
  const LocalFrame& frame = setup.local_frame;
  const Scene& scene = setup.scene;
  json objects = json::array();
  for (const Conductor& conductor : scene.conductors) {
    json line = json::array();
    for_sampled_vertices(conductor.points_enu_m, 48,
                         [&](const Eigen::Vector3d& p) { line.push_back(lat_lon(frame, p)); });
    objects.push_back({{"id", conductor.id}, {"class", "wire"}, {"line", line}});
  }
  for (const Cylinder& cylinder : scene.cylinders) {
    objects.push_back({{"id", cylinder.id},
                       {"class", to_string(cylinder.surface)},
                       {"at", lat_lon(frame, cylinder.base_enu_m)},
                       {"radius_m", cylinder.radius_m},
                       {"height_m", cylinder.height_m}});
  }
  for (const MeshObject& mesh : scene.meshes) {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& vertex : mesh.mesh.vertices) box.extend(vertex);
    objects.push_back({{"id", mesh.id},
                       {"class", to_string(mesh.surface)},
                       {"outline", box_outline(frame, {box.min().x(), box.max().x()},
                                               {box.min().y(), box.max().y()})}});
  }
  for (const FogVolume& fog : scene.fog) {
    json entry = {{"id", fog.id}, {"class", "fog"}};
    if (fog.shape == FogShape::box) {
      entry["outline"] = box_outline(frame, {fog.box.min().x(), fog.box.max().x()},
                                     {fog.box.min().y(), fog.box.max().y()});
    }
    objects.push_back(std::move(entry));
  }
  return objects;
}

// The ground's heights under the whole track (widened by 500 m) on a lattice of at most 200 × 200
// samples, for the map's hillshade and contours; null where the terrain is flat or absent (nothing
// to shade) and, per sample, where a DEM or grid has no height. Rows south to north, columns west
// to east; `bounds` the lattice's corners in WGS-84 ([south, west], [north, east]).
json terrain_view(const FlightSetup& setup) {
  const Terrain& terrain = setup.scene.terrain;
  if (terrain.kind != TerrainKind::grid && terrain.kind != TerrainKind::dem) return nullptr;
  const Trajectory& trajectory = setup.trajectory;
  Eigen::AlignedBox2d area;
  for (double t = trajectory.start_s(); t <= trajectory.end_s(); t += 0.5) {
    area.extend(Eigen::Vector2d(trajectory.pose_at(t).position_enu_m.head<2>()));
  }
  area.extend(Eigen::Vector2d(trajectory.pose_at(trajectory.end_s()).position_enu_m.head<2>()));
  constexpr double kMarginM = 500.0;
  area.min().array() -= kMarginM;
  area.max().array() += kMarginM;
  constexpr int kMaxSamples = 200;
  const double step = std::max(area.sizes().maxCoeff() / (kMaxSamples - 1), 1.0);
  const int cols = std::min(kMaxSamples, static_cast<int>(std::ceil(area.sizes().x() / step)) + 1);
  const int rows = std::min(kMaxSamples, static_cast<int>(std::ceil(area.sizes().y() / step)) + 1);
  json heights = json::array();
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const json u = ground_at(terrain, area.min().x() + col * step, area.min().y() + row * step);
      heights.push_back(u.is_null() ? u : json(std::round(u.get<double>() * 10) / 10));
      if (!u.is_null()) {
        lowest = std::min(lowest, u.get<double>());
        highest = std::max(highest, u.get<double>());
      }
    }
  }
  if (!(highest >= lowest)) return nullptr;  // no height anywhere under the track
  const Eigen::Vector2d far_corner(area.min().x() + (cols - 1) * step,
                                   area.min().y() + (rows - 1) * step);
  const LocalFrame& frame = setup.local_frame;
  return {{"cols", cols},
          {"rows", rows},
          {"step_m", step},
          {"lowest_m", lowest},
          {"highest_m", highest},
          {"bounds", json::array({lat_lon(frame, {area.min().x(), area.min().y(), 0.0}),
                                  lat_lon(frame, {far_corner.x(), far_corner.y(), 0.0})})},
          {"heights", heights}};
}

// A span's cross-section for the form: the ground and each of its conductors (ids "<span>/<n>")
// as (distance along the span from its first support, height) pairs, metres.
json span_section(const FlightSetup& setup, const SpanSpec& span) {
  const Eigen::Vector2d axis = span.to_en - span.from_en;
  const double length = axis.norm();
  const Eigen::Vector2d unit =
      length > 0.0 ? Eigen::Vector2d(axis / length) : Eigen::Vector2d::UnitX();
  json ground = json::array();
  constexpr int kSamples = 64;
  for (int k = 0; k <= kSamples; ++k) {
    const double d = length * k / kSamples;
    const Eigen::Vector2d at = span.from_en + d * unit;
    ground.push_back({std::round(d * 100) / 100, ground_at(setup.scene.terrain, at.x(), at.y())});
  }
  json conductors = json::array();
  const std::string prefix = span.id + "/";
  for (const Conductor& conductor : setup.scene.conductors) {
    if (!conductor.id.starts_with(prefix)) continue;
    json line = json::array();
    for_sampled_vertices(conductor.points_enu_m, 64, [&](const Eigen::Vector3d& p) {
      line.push_back({std::round((p.head<2>() - span.from_en).dot(unit) * 100) / 100,
                      std::round(p.z() * 100) / 100});
    });
    conductors.push_back({{"id", conductor.id}, {"line", line}});
  }
  return {{"length_m", length}, {"ground", ground}, {"conductors", conductors}};
}

// What the scenario declares, where the map's handles go: spans by their supports, poles and
// trees by their bases (the keys a drag rewrites).
json handles_view(const FlightSetup& setup) {
  const LocalFrame& frame = setup.local_frame;
  const SceneSpec& spec = setup.scenario.scene;
  json spans = json::array(), poles = json::array(), trees = json::array();
  const auto ground = [&](const Eigen::Vector2d& en) {
    const json u = ground_at(setup.scene.terrain, en.x(), en.y());
    return Eigen::Vector3d(en.x(), en.y(), u.is_null() ? 0.0 : u.get<double>());
  };
  for (const SpanSpec& span : spec.spans) {
    spans.push_back({{"id", span.id},
                     {"from", lat_lon(frame, ground(span.from_en))},
                     {"to", lat_lon(frame, ground(span.to_en))},
                     {"section", span_section(setup, span)}});
  }
  for (const Cylinder& pole : spec.poles) {
    poles.push_back({{"id", pole.id}, {"at", lat_lon(frame, pole.base_enu_m)}});
  }
  for (const Cylinder& tree : spec.trees) {
    trees.push_back({{"id", tree.id}, {"at", lat_lon(frame, tree.base_enu_m)}});
  }
  // A forest's area and the fog boxes, by their corners (east/north ranges in the scenario).
  json areas = json::array();
  if (spec.forest) {
    areas.push_back({{"kind", "forest"},
                     {"id", "forest"},
                     {"corners", box_outline(frame, spec.forest->e_range, spec.forest->n_range)}});
  }
  for (const FogVolume& fog : spec.fog) {
    if (fog.shape != FogShape::box) continue;
    areas.push_back({{"kind", "fog"},
                     {"id", fog.id},
                     {"corners", box_outline(frame, {fog.box.min().x(), fog.box.max().x()},
                                             {fog.box.min().y(), fog.box.max().y()})}});
  }
  return {{"spans", spans}, {"poles", poles}, {"trees", trees}, {"areas", areas}};
}

}  // namespace

nlohmann::json scene_view(const Simulation& simulation, double step_s) {
  const FlightSetup& setup = simulation.setup();
  if (!(step_s > 0.0)) throw Error("studio: the track's sample step must be positive");
  const Geodetic& origin = setup.scenario.origin;
  json view;
  view["origin"] = {{"lat", origin.lat_deg}, {"lon", origin.lon_deg}, {"h", origin.h_m}};
  view["track"] = track_view(setup, step_s);
  view["segment"] = {{"start_s", setup.scenario.trajectory.start_s},
                     {"frames", setup.frames},
                     {"end_s", simulation.frame_end_s(setup.frames - 1)}};
  view["objects"] = objects_view(setup);
  view["handles"] = handles_view(setup);
  view["terrain"] = terrain_view(setup);
  return view;
}

}  // namespace owsim::studio
