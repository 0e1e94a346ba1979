#pragma once
// A scenario (INTERFACE.md "Scenario file"): everything one simulated flight needs, as plain
// structs with the spec's defaults — the sensor's constants (SENSOR-SPEC §1–3, §7–8), its
// mount, the trajectory's source and the scene's objects, all in the local East-North-Up
// frame around `origin` (SENSOR-SPEC §4). io/scenario/scenario_loader.hpp fills it from YAML and
// validates every field; io/scenario/scene_builder.hpp turns `scene` into the geometry the engine
// traces. A program embedding owsim may also fill it in code.
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "detection/detector_params.hpp"
#include "geometry/forest.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "geometry/span.hpp"
#include "geometry/terrain.hpp"
#include "sensor/mounting.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

// Where the aircraft flies (INTERFACE.md `trajectory`): a planned route through waypoints or a
// recorded navigation file, read by the trajectory module.
struct TrajectorySpec {
  enum class Source { waypoints, file };
  Source source = Source::waypoints;

  // -- waypoints: straight legs at constant speed, banked turns (SENSOR-SPEC §4 pinned attitude);
  //    time 0 is the first waypoint
  double speed_mps = 40.0;
  std::vector<Eigen::Vector3d> waypoints_enu_m;  // local ENU metres, at least two
  double max_bank_deg = 30.0;

  // -- file: a recorded trajectory (SENSOR-SPEC §5)
  std::filesystem::path file;  // resolved against the scenario file's folder
  // hellsim | csv | sbet | ardupilot (an ArduPilot text log: GPS and ATT lines); without a
  // `format` key, csv for a .csv file, else hellsim
  std::string format = "hellsim";
  double tick_s = 0.0005;  // HellSim Time-Tag weight, seconds per count
  // The file's heading is magnetic: true heading = magnetic + magnetic_variation_deg (§5).
  bool heading_magnetic = false;
  double magnetic_variation_deg = 0.0;
  int smoothing_window = 9;  // Savitzky–Golay span (SENSOR-SPEC §5; the source's 5/4 is identity)
  int smoothing_degree = 3;

  // -- either source
  bool irs_noise = false;  // add the IRS error model of SENSOR-SPEC §5 table 2
  double start_s = 0.0;    // trajectory time of the first pulse (also ScanParams::start_s)
  std::optional<double> duration_s;  // nullopt: to the trajectory's end
};

// The objects the sensor sees, in local ENU metres.
struct SceneSpec {
  Terrain terrain;              // flat at u = 0 unless the scenario says otherwise
  std::vector<SpanSpec> spans;  // built into conductors and support poles by build_span
  // Poles and trees as placed: base_enu_m.z() is absolute — the loader puts a base given
  // without a height on the terrain (terrain.height_at).
  std::vector<Cylinder> poles;       // SurfaceClass::pole
  std::vector<Cylinder> trees;       // SurfaceClass::tree
  std::optional<ForestSpec> forest;  // generated with the scenario's seed
  std::vector<MeshObject> meshes;    // placed: vertices in local ENU metres
  std::vector<FogVolume> fog;        // key weather.fog (SENSOR-SPEC §10)
  double fog_backscatter_ratio_sr = 0.0154;  // key weather.backscatter_ratio_sr
};

// A file a scenario read (canonical), with the files reading it pulled in beside or below it (a
// mesh's materials and buffers, a shapefile's .dbf, a raster's sidecars): what a run folder copies
// so that its scenario.yaml reads only its own folder tree (io/scenario/scenario_as_flown.hpp).
struct InputFile {
  std::filesystem::path file;
  std::vector<std::filesystem::path> companions;
};

struct Scenario {
  std::string name;            // the output folder's default name; the file's stem by default
  std::filesystem::path path;  // the scenario file (empty when built in code)
  std::uint64_t seed = 0;      // every random draw derives from it (geometry/keyed_random.hpp)
  Geodetic origin;             // the local ENU frame's origin, WGS-84
  ScanParams scan;  // sensor.model and the scan constants; scan.start_s = trajectory.start_s
  ReceiverParams receiver;  // sensor.threshold, noise, returns, beam; atmosphere
  Mount mount;              // sensor.mount
  TrajectorySpec trajectory;
  SceneSpec scene;
  DetectorParams detector;  // the reference obstacle detector's `detector:` section (DETECTION-SPEC)
  std::vector<InputFile> input_files;  // every file its keys named, in the order read
};

}  // namespace owsim
