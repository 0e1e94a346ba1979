#include "io/scenario/scenario_loader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "geometry/conductor_layout.hpp"
#include "geometry/error.hpp"
#include "geometry/mesh_placement.hpp"
#include "geometry/number_text.hpp"
#include "geometry/utm.hpp"
#include "io/files/confined_path.hpp"
#include "io/scenario/dem_terrain.hpp"
#include "io/scenario/esri_ascii_grid.hpp"
#include "io/scenario/gdal_module.hpp"
#include "io/scenario/gis_lines.hpp"
#include "io/scenario/mesh_file.hpp"
#include "io/scenario/scenario_check.hpp"
#include "io/scenario/solar_position.hpp"
#include "io/scenario/value_ranges.hpp"
#include "io/scenario/yaml_reader.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/scan_params_check.hpp"
#include "sensor/weather.hpp"

namespace owsim {
namespace {

// Keys the sensor validators name differently from the file: the counter constants sit in
// sensor.counter, and the scan's start time is trajectory.start_s.
const std::map<std::string, std::string>& validator_keys() {
  static const std::map<std::string, std::string> keys = {
      {"sensor.speed_of_light_mps", "sensor.counter.speed_of_light_mps"},
      {"sensor.refractive_index_air", "sensor.counter.refractive_index_air"},
      {"sensor.timer_period_s", "sensor.counter.timer_period_s"},
      {"sensor.timeout_counts", "sensor.counter.timeout_counts"},
      {"sensor.start_s", "trajectory.start_s"},
  };
  return keys;
}

constexpr int kMaxForestTrees = 1'000'000;
constexpr double kTerrainHeightToleranceM = 1e-6;
constexpr int kTerrainIterations = 20;

double positive(const YamlValue& value) {
  const double x = value.number();
  if (!(x > 0.0)) value.fail("must be > 0, got " + number_text(x));
  return x;
}

double non_negative(const YamlValue& value) {
  const double x = value.number();
  if (!(x >= 0.0)) value.fail("must be ≥ 0, got " + number_text(x));
  return x;
}

double fraction(const YamlValue& value) {
  const double x = value.number();
  if (!(x >= 0.0 && x <= 1.0)) value.fail("must be between 0 and 1, got " + number_text(x));
  return x;
}

// on | off; also true | false, the same switch as YAML 1.1 reads it.
bool on_or_off(const YamlValue& value) {
  if (value.is_scalar()) {
    std::string text = value.text();
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (text == "on" || text == "true") return true;
    if (text == "off" || text == "false") return false;
  }
  value.fail("expected on or off, got " + value.describe());
}

int whole(const YamlValue& value) {
  return static_cast<int>(
      value.integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

Eigen::Vector2d min_max(const YamlValue& value) {
  const std::vector<double> pair = value.numbers(2);
  return {pair[0], pair[1]};
}

// What a position may say about its height.
enum class Height {
  required,   // waypoints: u or h
  optional,   // poles, trees: given → the base's height; absent → on the terrain
  forbidden,  // span supports: on the terrain, height from support_heights_m
};

class ScenarioReader {
 public:
  ScenarioReader(const YamlSource& source, const std::filesystem::path& path,
                 const RecordedTrack& recorded_track)
      : source_(source), folder_(path.parent_path()), recorded_track_(recorded_track) {
    scenario_.path = path;
  }

  Scenario read() {
    YamlMap root(source_.root());
    read_name(root.get("name"));
    if (const auto seed = root.get("seed")) scenario_.seed = seed->unsigned_integer();
    read_origin(root.require("origin"));
    // The scene last: a DEM is read for the flight's reach (the route and the counter's range).
    if (const auto sensor = root.get("sensor")) read_sensor(*sensor);
    if (const auto atmosphere = root.get("atmosphere")) read_atmosphere(*atmosphere);
    if (const auto sun = root.get("sun")) read_sun(*sun);
    read_trajectory(root.require("trajectory"));
    if (const auto scene = root.get("scene")) {
      read_scene(*scene);
    }
    if (const auto weather = root.get("weather")) read_weather(*weather);
    if (const auto detector = root.get("detector")) read_detector(*detector);
    root.finish();

    scenario_.scan.counter = scenario_.receiver.counter;
    scenario_.scan.start_s = scenario_.trajectory.start_s;
    try {
      validate(scenario_.scan);
      validate(scenario_.receiver);
    } catch (const Error& error) {
      source_.rethrow_at_key(error, "sensor", validator_keys());
    }
    return std::move(scenario_);
  }

 private:
  // ---- top level ----

  void read_name(const std::optional<YamlValue>& value) {
    if (!value) {
      scenario_.name = scenario_.path.stem().string();
      if (scenario_.name.empty()) scenario_.name = "scenario";
      return;
    }
    scenario_.name = value->text();
    const std::string& name = scenario_.name;
    if (name.empty() || name == "." || name == ".." ||
        name.find_first_of("/\\") != std::string::npos) {
      value->fail(
          "must be a non-empty name without '/' or '\\' (it names the output folder), got '" +
          name + "'");
    }
  }

  void read_origin(const YamlValue& value) {
    YamlMap map(value);
    Geodetic& origin = scenario_.origin;
    origin.lat_deg = map.require("lat").number();
    origin.lon_deg = map.require("lon").number();
    origin.h_m = map.require("h").number();
    map.finish();
    try {
      validate_geodetic(origin, "origin");
    } catch (const Error& error) {
      source_.rethrow_at_key(error, "origin");
    }
    frame_.emplace(origin);
  }

  // The file a key names: a local regular file in the scenario's folder tree (the current folder
  // for a scenario given as text), checked before anything opens it (io/files/confined_path.hpp).
  std::filesystem::path input_file(const YamlValue& value) const {
    try {
      return confined_file(folder_, value.text());
    } catch (const Error& error) {
      value.fail(error.what());
    }
  }
  // Records a file read (once) with the files it pulled in: those in its folder's tree.
  void add_input(const std::filesystem::path& file, std::vector<std::filesystem::path> companions) {
    for (const InputFile& known : scenario_.input_files) {
      if (known.file == file) return;
    }
    std::erase_if(companions, [&](const std::filesystem::path& companion) {
      return !inside_tree(file.parent_path(), companion);
    });
    scenario_.input_files.push_back({file, std::move(companions)});
  }

  // ---- sensor ----

  void read_sensor(const YamlValue& value) {
    YamlMap map(value);
    ScanParams& scan = scenario_.scan;
    ReceiverParams& receiver = scenario_.receiver;
    if (const auto model = map.get("model")) {
      scan.model = *parse_sensor_model(model->one_of({"milows", "hellas"}));
    }
    if (const auto mount = map.get("mount")) read_mount(*mount);
    receiver.beam.divergence_mrad = map.number_or("divergence_mrad", receiver.beam.divergence_mrad);
    receiver.beam.exit_radius_m = map.number_or("beam_exit_radius_m", receiver.beam.exit_radius_m);
    receiver.threshold = map.number_or("threshold", receiver.threshold);
    receiver.range_noise_sigma_m =
        map.number_or("range_noise_sigma_m", receiver.range_noise_sigma_m);
    if (const auto returns = map.get("returns")) {
      receiver.rule = returns->one_of({"first_second", "strongest"}) == "strongest"
                          ? ReturnRule::strongest
                          : ReturnRule::first_second;
    }
    receiver.min_return_separation_m =
        map.number_or("min_return_separation_m", receiver.min_return_separation_m);

    scan.prf_hz = map.number_or("prf_hz", scan.prf_hz);
    if (const auto fibers = map.get("fibers_per_line")) scan.fibers_per_line = whole(*fibers);
    if (const auto lines = map.get("lines_per_frame")) scan.lines_per_frame = whole(*lines);
    scan.sweep_deg = map.number_or("sweep_deg", scan.sweep_deg);
    scan.sawtooth_deg = map.number_or("sawtooth_deg", scan.sawtooth_deg);
    scan.frame_jitter_deg = map.number_or("frame_jitter_deg", scan.frame_jitter_deg);
    scan.look_into_turn_s = map.number_or("look_into_turn_s", scan.look_into_turn_s);
    scan.look_into_turn_limit_deg =
        map.number_or("look_into_turn_limit_deg", scan.look_into_turn_limit_deg);
    if (const auto order = map.get("fiber_order")) {
      scan.fiber_order = order->one_of({"crosstalk_resorted", "sequential"}) == "sequential"
                             ? FiberOrder::sequential
                             : FiberOrder::crosstalk_resorted;
    }
    if (const auto table = map.get("alpha_table_deg")) scan.alpha_table_deg = table->numbers();
    if (const auto reference = map.get("reference_counts")) {
      scan.reference_counts = static_cast<std::uint16_t>(reference->integer(0, kCounterMax));
    }
    scan.hellas_mirror_angle_factor_deg =
        map.number_or("hellas_mirror_angle_factor_deg", scan.hellas_mirror_angle_factor_deg);
    if (const auto counter = map.get("counter")) read_counter(*counter);
    if (const auto statistics = map.get("receiver")) read_receiver(*statistics);
    map.finish();
  }

  // sensor.receiver: the receiver's statistics (SENSOR-SPEC §11)
  void read_receiver(const YamlValue& value) {
    YamlMap map(value);
    ReceiverNoiseParams& noise = scenario_.receiver.noise;
    if (const auto on = map.get("noise")) noise.on = on_or_off(*on);
    noise.noise_at_1km = map.number_or("noise_at_1km", noise.noise_at_1km);
    noise.pulse_width_ns = map.number_or("pulse_width_ns", noise.pulse_width_ns);
    noise.sun_noise = map.number_or("sun_noise", noise.sun_noise);
    noise.sky_noise = map.number_or("sky_noise", noise.sky_noise);
    map.finish();
  }

  void read_mount(const YamlValue& value) {
    YamlMap map(value);
    Mount& mount = scenario_.mount;
    mount.roll_deg = map.number_or("roll_deg", mount.roll_deg);
    mount.pitch_deg = map.number_or("pitch_deg", mount.pitch_deg);
    mount.yaw_deg = map.number_or("yaw_deg", mount.yaw_deg);
    if (const auto lever = map.get("lever_arm_m")) {
      const std::vector<double> xyz = lever->numbers(3);
      mount.lever_arm_m = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    }
    map.finish();
  }

  void read_counter(const YamlValue& value) {
    YamlMap map(value);
    RangeCounterParams& counter = scenario_.receiver.counter;
    counter.speed_of_light_mps = map.number_or("speed_of_light_mps", counter.speed_of_light_mps);
    counter.refractive_index_air =
        map.number_or("refractive_index_air", counter.refractive_index_air);
    counter.timer_period_s = map.number_or("timer_period_s", counter.timer_period_s);
    if (const auto timeout = map.get("timeout_counts")) {
      counter.timeout_counts = static_cast<std::uint16_t>(timeout->integer(1, kCounterMax));
    }
    map.finish();
  }

  void read_atmosphere(const YamlValue& value) {
    YamlMap map(value);
    Atmosphere& atmosphere = scenario_.receiver.atmosphere;
    const std::optional<YamlValue> transmission = map.get("transmission");
    const std::optional<YamlValue> visibility = map.get("visibility_km");
    if (transmission && visibility) {
      visibility->fail("give transmission or visibility_km, not both");
    }
    if (transmission) atmosphere.transmission = transmission->number();
    if (visibility) atmosphere.visibility_km = visibility->number();
    atmosphere.wavelength_um = map.number_or("wavelength_um", atmosphere.wavelength_um);
    map.finish();
  }

  // sun: {elevation_deg, azimuth_deg} or {time_utc} (SENSOR-SPEC §11 sunlight); a time is the
  // sun's position at the origin (io/scenario/solar_position.hpp).
  void read_sun(const YamlValue& value) {
    YamlMap map(value);
    const std::optional<YamlValue> time = map.get("time_utc");
    const std::optional<YamlValue> elevation = map.get("elevation_deg");
    const std::optional<YamlValue> azimuth = map.get("azimuth_deg");
    map.finish();
    if (time && (elevation || azimuth)) {
      time->fail("give time_utc or elevation_deg and azimuth_deg, not both");
    }
    if (!time && !elevation && !azimuth) {
      map.fail("needs {elevation_deg, azimuth_deg} or {time_utc: \"2026-06-21T10:30:00Z\"}");
    }
    SunPosition& sun = scenario_.receiver.sun;
    if (time) {
      try {
        sun = solar_position(parse_utc_time(time->text()), scenario_.origin.lat_deg,
                             scenario_.origin.lon_deg);
      } catch (const Error& error) {
        time->fail(error.what());
      }
    } else {
      const double elevation_deg = map.require("elevation_deg").number();
      sun = sun_at_angles(elevation_deg, map.require("azimuth_deg").number());
    }
  }

  // detector: the reference obstacle detector's parameters (DETECTION-SPEC; every key optional,
  // detection/detector_params.hpp's defaults and ranges).
  void read_detector(const YamlValue& value) {
    YamlMap map(value);
    DetectorParams& detector = scenario_.detector;
    for (const DetectorKey& key : detector_keys()) {
      const std::optional<YamlValue> item = map.get(key.name);
      if (!item) continue;
      if (key.number == nullptr) {
        detector.min_points = static_cast<int>(item->integer(static_cast<std::int64_t>(key.min),
                                                             static_cast<std::int64_t>(key.max)));
      } else {
        detector.*key.number = item->number();
      }
      for (const std::string& problem : detector_param_problems(detector)) {
        if (problem.starts_with(std::string(key.name) + ": ")) {
          item->fail(problem.substr(key.name.size() + 2));
        }
      }
    }
    map.finish();
  }

  // ---- trajectory ----

  void read_trajectory(const YamlValue& value) {
    YamlMap map(value);
    TrajectorySpec& trajectory = scenario_.trajectory;
    const std::optional<YamlValue> waypoints = map.get("waypoints");
    const std::optional<YamlValue> file = map.get("file");
    if (waypoints && file) {
      file->fail("a trajectory has exactly one source: give waypoints or file, not both");
    }
    if (!waypoints && !file) map.fail("needs a source: waypoints or file");
    if (waypoints) {
      trajectory.source = TrajectorySpec::Source::waypoints;
      for (const char* key :
           {"format", "tick_s", "heading", "magnetic_variation_deg", "smoothing"}) {
        if (map.contains(key)) map.get(key)->fail("applies only to a trajectory file");
      }
      read_waypoints(*waypoints);
    } else {
      trajectory.source = TrajectorySpec::Source::file;
      read_trajectory_file(map, *file);
    }
    trajectory.irs_noise = map.boolean_or("irs_noise", trajectory.irs_noise);
    if (const auto start = map.get("start_s")) trajectory.start_s = non_negative(*start);
    if (const auto duration = map.get("duration_s")) trajectory.duration_s = positive(*duration);
    map.finish();
  }

  void read_waypoints(const YamlValue& value) {
    YamlMap map(value);
    TrajectorySpec& trajectory = scenario_.trajectory;
    trajectory.speed_mps = positive(map.require("speed_mps"));
    const YamlValue points = map.require("points");
    const std::vector<YamlValue> items = points.items();
    if (items.size() < 2) {
      points.fail("a route needs at least 2 waypoints, got " + std::to_string(items.size()));
    }
    trajectory.waypoints_enu_m.clear();
    for (const YamlValue& item : items) {
      const Eigen::Vector3d point = read_position(item, Height::required);
      if (!trajectory.waypoints_enu_m.empty() && point == trajectory.waypoints_enu_m.back()) {
        item.fail("repeats the previous waypoint");
      }
      trajectory.waypoints_enu_m.push_back(point);
    }
    if (const auto bank = map.get("max_bank_deg")) {
      trajectory.max_bank_deg = bank->number();
      if (!(trajectory.max_bank_deg > 0.0 && trajectory.max_bank_deg < 90.0)) {
        bank->fail("must be in (0, 90) degrees, got " + number_text(trajectory.max_bank_deg));
      }
    }
    map.finish();
  }

  void read_trajectory_file(YamlMap& map, const YamlValue& file) {
    TrajectorySpec& trajectory = scenario_.trajectory;
    trajectory.file = input_file(file);
    add_input(trajectory.file, {});
    if (const auto format = map.get("format")) {
      trajectory.format = format->one_of({"hellsim", "csv", "sbet", "ardupilot"});
    } else {
      trajectory.format = trajectory.file.extension() == ".csv" ? "csv" : "hellsim";
    }
    if (const auto tick = map.get("tick_s")) {
      if (trajectory.format != "hellsim") tick->fail("applies only to format hellsim");
      trajectory.tick_s = positive(*tick);
    }
    const std::optional<YamlValue> heading = map.get("heading");
    trajectory.heading_magnetic = heading && heading->one_of({"true", "magnetic"}) == "magnetic";
    const std::optional<YamlValue> variation = map.get("magnetic_variation_deg");
    if (trajectory.heading_magnetic && !variation) {
      heading->fail("heading: magnetic needs magnetic_variation_deg (true = magnetic + variation)");
    }
    if (variation) {
      if (!trajectory.heading_magnetic) variation->fail("applies only with heading: magnetic");
      trajectory.magnetic_variation_deg = variation->number();
      if (!(std::abs(trajectory.magnetic_variation_deg) <= 180.0)) {
        variation->fail("must be in [-180, 180] degrees, got " +
                        number_text(trajectory.magnetic_variation_deg));
      }
    }
    if (const auto smoothing = map.get("smoothing")) read_smoothing(*smoothing);
  }

  void read_smoothing(const YamlValue& value) {
    YamlMap map(value);
    TrajectorySpec& trajectory = scenario_.trajectory;
    if (const auto window = map.get("window")) {
      trajectory.smoothing_window = static_cast<int>(window->integer(1, 10'001));
      if (trajectory.smoothing_window % 2 == 0) {
        window->fail("a Savitzky–Golay window must be odd, got " +
                     std::to_string(trajectory.smoothing_window));
      }
    }
    if (const auto degree = map.get("degree")) {
      trajectory.smoothing_degree = static_cast<int>(degree->integer(0, 10'000));
    }
    if (trajectory.smoothing_degree >= trajectory.smoothing_window) {
      const YamlValue degree = map.contains("degree") ? *map.get("degree") : value;
      degree.fail("the degree (" + std::to_string(trajectory.smoothing_degree) +
                  ") must be below the window (" + std::to_string(trajectory.smoothing_window) +
                  ")");
    }
    map.finish();
  }

  // ---- weather (SENSOR-SPEC §10) ----

  // weather: {backscatter_ratio_sr, fog: [{id, visibility_m, box | layer}]}; a volume without a
  // shape fills the whole sky.
  void read_weather(const YamlValue& value) {
    YamlMap map(value);
    if (const auto ratio = map.get("backscatter_ratio_sr")) {
      scenario_.scene.fog_backscatter_ratio_sr = ratio->number();
      if (!(scenario_.scene.fog_backscatter_ratio_sr >= 0.0 &&
            std::isfinite(scenario_.scene.fog_backscatter_ratio_sr))) {
        ratio->fail("must be a finite number ≥ 0 (sr⁻¹)");
      }
    }
    if (const auto fog = map.get("fog")) {
      const std::vector<YamlValue> volumes = fog->items();
      if (volumes.size() > kMaxFogVolumes) {
        fog->fail("at most " + std::to_string(kMaxFogVolumes) + " volumes, got " +
                  std::to_string(volumes.size()));
      }
      for (const YamlValue& item : volumes) read_fog_volume(item);
    }
    map.finish();
  }

  void read_fog_volume(const YamlValue& value) {
    YamlMap map(value);
    FogVolume volume;
    volume.id = read_id(map);
    volume.visibility_m = positive(map.require("visibility_m"));
    const std::optional<YamlValue> box = map.get("box");
    const std::optional<YamlValue> layer = map.get("layer");
    if (box && layer) layer->fail("a volume is a box or a layer, not both");
    if (layer) {
      YamlMap heights(*layer);
      volume.shape = FogShape::layer;
      volume.base_m = heights.require("base_m").number();
      const YamlValue top = heights.require("top_m");
      volume.top_m = top.number();
      heights.finish();
      if (!(volume.top_m > volume.base_m)) {
        top.fail("the layer's top must lie above its base (" + number_text(volume.base_m) +
                 " m), got " + number_text(volume.top_m));
      }
    }
    if (box) {
      YamlMap sides(*box);
      volume.shape = FogShape::box;
      Eigen::Vector3d low, high;
      const char* axes[3] = {"e", "n", "u"};
      for (int axis = 0; axis < 3; ++axis) {
        const YamlValue side = sides.require(axes[axis]);
        const Eigen::Vector2d range = min_max(side);
        if (!(range[1] > range[0])) side.fail("expected [min, max] with min < max");
        low[axis] = range[0];
        high[axis] = range[1];
      }
      sides.finish();
      volume.box = Eigen::AlignedBox3d(low, high);
    }
    map.finish();
    scenario_.scene.fog.push_back(std::move(volume));
  }

  // ---- positions ----

  Eigen::Vector3d read_position(const YamlValue& value, Height height) {
    YamlMap map(value);
    const bool enu = map.contains("e") || map.contains("n") || map.contains("u");
    const bool geodetic = map.contains("lat") || map.contains("lon");
    const bool utm = map.contains("utm");
    const bool has_h = map.contains("h");
    std::string forms;
    for (const auto& [used, form] :
         {std::pair{enu, "{e, n, u}"}, std::pair{geodetic, "{lat, lon, h}"},
          std::pair{utm, "{utm, h}"}}) {
      if (!used) continue;
      if (!forms.empty()) forms += " and ";
      forms += form;
    }
    if (static_cast<int>(enu) + static_cast<int>(geodetic) + static_cast<int>(utm) > 1) {
      value.fail("mixes the " + forms + " forms of a position; use one");
    }
    if (enu && has_h) value.fail("mixes the {e, n, u} form with h; use u for a local height");
    if (forms.empty()) {
      value.fail(
          "expected a position {e, n, u}, {lat, lon, h} or {utm: \"32U 634000 5394000\", h}");
    }
    const char* vertical = enu ? "u" : "h";
    if (height == Height::forbidden && map.contains(vertical)) {
      map.get(vertical)->fail(
          "a span support stands on the terrain; its height is set by support_heights_m");
    }
    if (height == Height::required) (void)map.require(vertical);

    if (enu) {
      const double e = map.require("e").number();
      const double n = map.require("n").number();
      const std::optional<double> u = map.optional_number("u");
      map.finish();
      if (u) return {e, n, *u};
      if (height == Height::forbidden) return {e, n, 0.0};  // build_span reads the terrain
      return {e, n, ground_u_m(e, n, value)};
    }

    Geodetic point;
    std::optional<double> h;
    if (geodetic) {
      point.lat_deg = map.require("lat").number();
      point.lon_deg = map.require("lon").number();
      h = map.optional_number("h");
      map.finish();
    } else {
      const YamlValue text = map.require("utm");
      h = map.optional_number("h");
      map.finish();
      try {
        point = geodetic_from_utm(parse_utm(text.text()), 0.0);
      } catch (const Error& error) {
        text.fail(error.what());
      }
    }
    point.h_m = h.value_or(scenario_.origin.h_m);
    try {
      validate_geodetic(point, value.path());
      if (h) return frame_->enu_from_geodetic(point);
    } catch (const Error& error) {
      source_.rethrow_at_key(error, value.path());
    }
    return on_terrain(point, value);
  }

  // The point at the latitude and longitude of `point` whose local height is the terrain's:
  // the ellipsoidal height is corrected until the two agree.
  Eigen::Vector3d on_terrain(Geodetic point, const YamlValue& value) const {
    Eigen::Vector3d enu = frame_->enu_from_geodetic(point);
    for (int i = 0; i < kTerrainIterations; ++i) {
      const double gap_m = ground_u_m(enu.x(), enu.y(), value) - enu.z();
      if (std::abs(gap_m) < kTerrainHeightToleranceM) break;
      point.h_m += gap_m;
      enu = frame_->enu_from_geodetic(point);
    }
    enu.z() = ground_u_m(enu.x(), enu.y(), value);
    return enu;
  }

  double ground_u_m(double e_m, double n_m, const YamlValue& value) const {
    try {
      return scenario_.scene.terrain.height_at(e_m, n_m);
    } catch (const Error& error) {
      value.fail(error.what());
    }
  }

  // ---- scene ----

  void read_scene(const YamlValue& value) {
    YamlMap map(value);
    read_terrain(map.get("terrain"));
    if (const auto spans = map.get("spans")) {
      for (const YamlValue& item : spans->items()) read_span(item);
    }
    if (const auto lines = map.get("power_lines")) {
      for (const YamlValue& item : lines->items()) read_power_lines(item);
    }
    if (const auto poles = map.get("poles")) {
      for (const YamlValue& item : poles->items()) {
        scenario_.scene.poles.push_back(read_cylinder(item, SurfaceClass::pole, 0.3));
      }
    }
    if (const auto trees = map.get("trees")) {
      for (const YamlValue& item : trees->items()) {
        scenario_.scene.trees.push_back(read_cylinder(item, SurfaceClass::tree, 0.2));
      }
    }
    if (const auto forest = map.get("forest")) read_forest(*forest);
    if (const auto meshes = map.get("meshes")) {
      for (const YamlValue& item : meshes->items()) read_mesh(item);
    }
    map.finish();
  }

  // meshes: a model file placed at a position (on the terrain when it has no height), turned by
  // yaw_deg (clockwise from north), scaled, of class building (default), pole or tree.
  void read_mesh(const YamlValue& value) {
    YamlMap map(value);
    MeshObject mesh;
    mesh.id = read_id(map);
    const YamlValue file_value = map.require("file");
    if (file_value.text().empty()) file_value.fail("expected a file name, got ''");
    MeshPlacement placement;
    placement.at_enu_m = read_position(map.require("at"), Height::optional);
    if (const auto yaw = map.optional_number("yaw_deg")) placement.yaw_deg = *yaw;
    if (const auto scale = map.get("scale")) placement.scale = positive(*scale);
    if (const auto up = map.get("up_axis")) {
      placement.up = up->one_of({"z", "y"}) == "y" ? ModelUpAxis::y : ModelUpAxis::z;
    }
    if (const auto surface = map.get("class")) {
      mesh.surface = *surface_class_from_string(surface->one_of({"building", "pole", "tree"}));
    }
    if (const auto given = map.get("reflectivity")) mesh.reflectivity = fraction(*given);
    map.finish();
    const std::filesystem::path file = input_file(file_value);
    try {
      MeshFile read = read_mesh_file(file);
      mesh.mesh = placed_mesh(read.mesh, placement);
      add_input(file, std::move(read.companions));
    } catch (const Error& error) {
      file_value.fail(error.what());
    }
    scenario_.scene.meshes.push_back(std::move(mesh));
  }

  void read_terrain(const std::optional<YamlValue>& value) {
    Terrain& terrain = scenario_.scene.terrain;
    if (!value) return;  // flat at u = 0
    if (value->is_null()) {
      terrain.kind = TerrainKind::none;
      return;
    }
    if (value->is_scalar()) {
      if (value->text() != "none") {
        value->fail("expected none, {flat_u: U}, {grid: FILE} or {dem: FILE}, got " +
                    value->describe());
      }
      terrain.kind = TerrainKind::none;
      return;
    }
    YamlMap map(*value);
    const std::optional<YamlValue> flat = map.get("flat_u");
    const std::optional<YamlValue> grid = map.get("grid");
    const std::optional<YamlValue> dem = map.get("dem");
    if (static_cast<int>(flat.has_value()) + static_cast<int>(grid.has_value()) +
            static_cast<int>(dem.has_value()) >
        1) {
      (dem ? *dem : *grid).fail("give one of flat_u, grid and dem");
    }
    if (!flat && !grid && !dem) map.fail("needs flat_u, grid or dem (or write terrain: none)");
    if (const auto reflectivity = map.get("reflectivity")) {
      terrain.reflectivity = fraction(*reflectivity);
    }
    map.finish();
    if (dem) {
      read_dem(*dem);
      return;
    }
    if (flat) {
      terrain.kind = TerrainKind::flat;
      terrain.flat_u_m = flat->number();
      return;
    }
    const std::filesystem::path file = input_file(*grid);
    add_input(file, {});
    try {
      terrain.grid = read_esri_ascii_grid(file.string());
      terrain.grid.validate(file.string());
    } catch (const FileError& error) {
      try {
        grid->fail(error.what());
      } catch (const Error& located) {
        throw FileError(located.what());  // still a file that cannot be read, now with its line
      }
    } catch (const Error& error) {
      grid->fail(error.what());
    }
    terrain.kind = TerrainKind::grid;
  }

  // terrain.dem: the DEM's posts within the flight's reach (the route, or the recorded track
  // when the caller can read it, widened by the counter's timeout range; else the whole raster),
  // and the flight must lie on it.
  void read_dem(const YamlValue& value) {
    const std::filesystem::path file = input_file(value);
    Terrain& terrain = scenario_.scene.terrain;
    const TrajectorySpec& route = scenario_.trajectory;
    std::vector<Eigen::Vector2d> flight;
    if (route.source == TrajectorySpec::Source::waypoints) {
      for (const Eigen::Vector3d& point : route.waypoints_enu_m) flight.push_back(point.head<2>());
    } else if (recorded_track_) {
      flight = recorded_track_(scenario_, *frame_);
    }
    std::optional<Eigen::AlignedBox2d> reach;
    if (!flight.empty()) {
      reach.emplace();
      for (const Eigen::Vector2d& point : flight) reach->extend(point);
      const double range_m = timeout_range_m(scenario_.receiver.counter);
      reach->min().array() -= range_m;
      reach->max().array() += range_m;
    }
    try {
      terrain.dem = std::make_shared<const PostLattice>(read_dem_terrain(file, *frame_, reach));
      add_input(file, dataset_companions(file, false));
    } catch (const Error& error) {
      value.fail(error.what());
    }
    terrain.kind = TerrainKind::dem;
    for (const Eigen::Vector2d& point : flight) {
      if (!terrain.dem->covers(point.x(), point.y())) {
        value.fail(file.string() + ": does not cover the flight (at e = " + number_text(point.x()) +
                   ", n = " + number_text(point.y()) + " m)");
      }
    }
  }

  std::string read_id(YamlMap& map) {
    const YamlValue value = map.require("id");
    std::string id = value.text();
    if (const std::string problem = object_id_problem(id); !problem.empty()) value.fail(problem);
    const auto [found, inserted] = ids_.emplace(id, value.line());
    if (!inserted) {
      value.fail("duplicate id '" + id + "' (first used at line " + std::to_string(found->second) +
                 ")");
    }
    return id;
  }

  void read_span(const YamlValue& value) {
    YamlMap map(value);
    SpanSpec span;
    span.id = read_id(map);
    span.from_en = read_position(map.require("from"), Height::forbidden).head<2>();
    span.to_en = read_position(map.require("to"), Height::forbidden).head<2>();
    read_span_properties(map, span);
    map.finish();
    add_span(std::move(span), value.path());
  }

  // The keys a span and a power line share: heights, sag, layout, conductor, supports.
  void read_span_properties(YamlMap& map, SpanSpec& span) {
    if (const auto heights = map.get("support_heights_m")) {
      const std::vector<double> h = heights->numbers(2);
      span.support_height_1_m = h[0];
      span.support_height_2_m = h[1];
    }
    span.lowest_point_m = map.number_or("lowest_point_m", span.lowest_point_m);
    if (const auto layout = map.get("layout")) span.offsets = read_layout(*layout);
    if (const auto conductor = map.get("conductor")) {
      YamlMap wire(*conductor);
      if (const auto diameter = wire.get("diameter_mm")) {
        span.conductor_diameter_m = diameter->number() / 1000.0;
      }
      span.conductor_reflectivity = wire.number_or("reflectivity", span.conductor_reflectivity);
      wire.finish();
    }
    if (const auto supports = map.get("supports")) {
      YamlMap pole(*supports);
      if (const auto kind = pole.get("kind")) {
        span.support_poles = kind->one_of({"pole", "none"}) == "pole";
      }
      for (const char* key : {"diameter_m", "reflectivity"}) {
        if (!span.support_poles && pole.contains(key)) {
          pole.get(key)->fail("applies only with kind: pole");
        }
      }
      span.pole_diameter_m = pole.number_or("diameter_m", span.pole_diameter_m);
      span.pole_reflectivity = pole.number_or("reflectivity", span.pole_reflectivity);
      pole.finish();
    }
  }

  void add_span(SpanSpec span, const std::string& where) {
    try {
      (void)build_span(span, scenario_.scene.terrain, where);
    } catch (const Error& error) {
      source_.rethrow_at_key(error, where);
    }
    scenario_.scene.spans.push_back(std::move(span));
  }

  // power_lines: every LineString of a GIS file is a line of spans between its vertices (the
  // towers): span k of line L is "L/k" (k from 1), its tower poles "L/tower-k" are shared by the
  // spans that meet there. L is the feature's `name` property, else the entry's id (with "-i" for
  // the i-th line when the file holds several), else the file's stem with "-i". A feature's
  // properties layout, support_height_m, lowest_point_m, diameter_mm and pole_diameter_m override
  // the entry's.
  void read_power_lines(const YamlValue& value) {
    YamlMap map(value);
    const YamlValue file_value = map.require("file");
    const std::filesystem::path file = input_file(file_value);
    std::string prefix = file.stem().string();
    if (const auto id = map.get("id")) {
      prefix = id->text();
      if (prefix.empty() || prefix.find('/') != std::string::npos) {
        id->fail("a line id must be non-empty and without '/'");
      }
    }
    SpanSpec common;
    read_span_properties(map, common);
    map.finish();
    std::vector<GisLine> lines;
    try {
      lines = read_gis_lines(file);
      add_input(file, dataset_companions(file, true));
    } catch (const Error& error) {
      file_value.fail(error.what());
    }
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const GisLine& line = lines[i];
      const std::string feature =
          file.filename().string() + " feature " + std::to_string(line.feature);
      std::string line_name = lines.size() == 1 ? prefix : prefix + "-" + std::to_string(i + 1);
      SpanSpec spec = common;
      try {
        apply_line_properties(line.properties, line_name, spec);
      } catch (const Error& error) {
        file_value.fail(feature + ": " + error.what());
      }
      if (spec.support_height_1_m != spec.support_height_2_m) {
        file_value.fail(feature +
                        ": a line's towers share one height: give support_heights_m "
                        "[h, h] or the property support_height_m");
      }
      if (line.lon_lat.size() < 2) {
        file_value.fail(feature + ": a line needs at least 2 towers, got " +
                        std::to_string(line.lon_lat.size()));
      }
      if (!ids_.emplace(line_name, file_value.line()).second) {
        file_value.fail(feature + ": duplicate line name '" + line_name + "'");
      }
      add_line(line, line_name, spec, file_value, feature);
    }
  }

  static void apply_line_properties(const nlohmann::json& properties, std::string& name,
                                    SpanSpec& spec) {
    const auto number = [&](const char* key) -> std::optional<double> {
      if (!properties.contains(key)) return std::nullopt;
      if (!properties[key].is_number())
        throw Error(std::string("property ") + key + " is not a number");
      return properties[key].get<double>();
    };
    if (properties.contains("name")) {
      name = properties["name"].is_string() ? properties["name"].get<std::string>()
                                            : properties["name"].dump();
      if (name.empty() || name.find('/') != std::string::npos) {
        throw Error("property name must be non-empty and without '/'");
      }
    }
    if (properties.contains("layout")) {
      const auto kind = properties["layout"].is_string()
                            ? layout_kind_from_string(properties["layout"].get<std::string>())
                            : std::nullopt;
      if (!kind) throw Error("property layout must be single, tri or sept");
      spec.offsets = conductor_offsets(*kind);
    }
    if (const auto h = number("support_height_m")) {
      spec.support_height_1_m = *h;
      spec.support_height_2_m = *h;
    }
    if (const auto s = number("lowest_point_m")) spec.lowest_point_m = *s;
    if (const auto d = number("diameter_mm")) spec.conductor_diameter_m = *d / 1000.0;
    if (const auto d = number("pole_diameter_m")) spec.pole_diameter_m = *d;
  }

  // The spans between consecutive towers, and one pole per tower when the line has supports.
  void add_line(const GisLine& line, const std::string& name, const SpanSpec& spec,
                const YamlValue& where, const std::string& feature) {
    std::vector<Eigen::Vector3d> towers;
    for (const Eigen::Vector2d& lon_lat : line.lon_lat) {
      Geodetic point{lon_lat.y(), lon_lat.x(), scenario_.origin.h_m};
      try {
        validate_geodetic(point, feature);
      } catch (const Error& error) {
        where.fail(error.what());
      }
      towers.push_back(on_terrain(point, where));
    }
    for (std::size_t k = 0; k + 1 < towers.size(); ++k) {
      SpanSpec span = spec;
      span.id = name + "/" + std::to_string(k + 1);
      span.from_en = towers[k].head<2>();
      span.to_en = towers[k + 1].head<2>();
      span.support_poles = false;
      if (span.from_en == span.to_en) {
        where.fail(feature + ": towers " + std::to_string(k + 1) + " and " + std::to_string(k + 2) +
                   " coincide");
      }
      add_span(std::move(span), where.path());
    }
    if (!spec.support_poles) return;
    for (std::size_t k = 0; k < towers.size(); ++k) {
      Cylinder pole;
      pole.surface = SurfaceClass::pole;
      pole.id = name + "/tower-" + std::to_string(k + 1);
      pole.base_enu_m = towers[k];
      pole.height_m = spec.support_height_1_m;
      pole.radius_m = 0.5 * spec.pole_diameter_m;
      pole.reflectivity = spec.pole_reflectivity;
      scenario_.scene.poles.push_back(std::move(pole));
    }
  }

  static std::vector<ConductorOffset> read_layout(const YamlValue& value) {
    if (value.is_scalar()) {
      return conductor_offsets(*layout_kind_from_string(value.one_of({"single", "tri", "sept"})));
    }
    if (!value.is_list()) {
      value.fail("expected single | tri | sept or a list [[dy, dz], ...], got " + value.describe());
    }
    std::vector<ConductorOffset> offsets;
    for (const YamlValue& item : value.items()) {
      const std::vector<double> pair = item.numbers(2);
      offsets.push_back({pair[0], pair[1]});
    }
    if (offsets.empty()) value.fail("a span needs at least one conductor");
    return offsets;
  }

  Cylinder read_cylinder(const YamlValue& value, SurfaceClass surface, double reflectivity) {
    YamlMap map(value);
    Cylinder cylinder;
    cylinder.surface = surface;
    cylinder.id = read_id(map);
    cylinder.base_enu_m = read_position(map.require("at"), Height::optional);
    cylinder.height_m = positive(map.require("height_m"));
    cylinder.radius_m = 0.5 * positive(map.require("diameter_m"));
    const std::optional<YamlValue> given = map.get("reflectivity");
    cylinder.reflectivity = given ? fraction(*given) : reflectivity;
    map.finish();
    return cylinder;
  }

  void read_forest(const YamlValue& value) {
    YamlMap map(value);
    ForestSpec forest;
    if (const auto count = map.get("count")) {
      forest.count = static_cast<int>(count->integer(0, kMaxForestTrees));
    }
    if (const auto area = map.get("area")) {
      YamlMap box(*area);
      if (const auto e = box.get("e")) forest.e_range = min_max(*e);
      if (const auto n = box.get("n")) forest.n_range = min_max(*n);
      box.finish();
    }
    if (const auto height = map.get("height_m")) {
      const Eigen::Vector2d range = min_max(*height);
      forest.height_min_m = range[0];
      forest.height_max_m = range[1];
    }
    if (const auto diameter = map.get("diameter_m")) {
      const Eigen::Vector2d range = min_max(*diameter);
      forest.diameter_min_m = range[0];
      forest.diameter_max_m = range[1];
    }
    forest.reflectivity = map.number_or("reflectivity", forest.reflectivity);
    map.finish();
    try {
      (void)generate_forest(forest, scenario_.seed, scenario_.scene.terrain, value.path());
    } catch (const Error& error) {
      source_.rethrow_at_key(error, value.path());
    }
    scenario_.scene.forest = forest;
  }

  const YamlSource& source_;
  std::filesystem::path folder_;
  Scenario scenario_;
  std::optional<LocalFrame> frame_;
  const RecordedTrack& recorded_track_;
  std::map<std::string, int> ids_;  // object id → line of first use
};

}  // namespace

Scenario load_scenario(const std::filesystem::path& path, const RecordedTrack& recorded_track) {
  YamlSource source = YamlSource::from_file(path);
  source.check_ranges_with(out_of_range_problem);
  return ScenarioReader(source, path, recorded_track).read();
}

Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& path,
                            const RecordedTrack& recorded_track) {
  YamlSource source = YamlSource::from_text(yaml, path.string());
  source.check_ranges_with(out_of_range_problem);
  return ScenarioReader(source, path, recorded_track).read();
}

}  // namespace owsim
