// Protects the bundled examples (examples/*.yaml, INTERFACE.md "Scenario file"): each loads,
// holds the scene it promises, fits its trajectory, and runs through `owsim run` with a short
// --duration into the expected files (d64 size, CSV headers and rows, LAS/PLY point counts and
// sizes, summary totals and objects, the quick-look PNGs); and the bundled HellSim file is what its
// script writes and turns through north.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"
#include "io/trajectory/hellsim_reader.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

constexpr int kPulsesPerFrame = 20'352;        // SENSOR-SPEC §2
constexpr double kFrameS = 20'352 / 61'111.0;  // SENSOR-SPEC §2 pinned timing
constexpr const char* kPointsHeader =
    "frame,pulse,line,fiber,return,time_s,range_m,counter,e_m,n_m,u_m,lat_deg,lon_deg,h_m,class,"
    "object,energy_rel,incidence_deg";
constexpr const char* kTrajectoryHeader =
    "time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg";

const fs::path kExamples = fs::path(OWSIM_SOURCE_DIR) / "examples";
const std::vector<std::string> kExampleNames = {"single_span",    "pylon_line",    "corridor",
                                                "hellsim_flight", "real_corridor", "fog_bank"};

fs::path example(const std::string& name) { return kExamples / (name + ".yaml"); }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) lines.push_back(line);
  return lines;
}

std::uint64_t little_endian(const std::string& bytes, std::size_t offset, int size) {
  std::uint64_t value = 0;
  for (int b = size - 1; b >= 0; --b) {
    value = (value << 8) | static_cast<unsigned char>(bytes[offset + static_cast<std::size_t>(b)]);
  }
  return value;
}

std::size_t count_of(const Scene& scene, SurfaceClass surface) {
  return static_cast<std::size_t>(
      std::count_if(scene.cylinders.begin(), scene.cylinders.end(),
                    [&](const Cylinder& c) { return c.surface == surface; }));
}

TEST(Examples, FolderHoldsTheSixExamples) {
  std::set<std::string> found;
  for (const auto& entry : fs::directory_iterator(kExamples)) {
    // A sweep file sits beside its base scenario (it may read only its own folder tree).
    if (entry.path().extension() == ".yaml" && !entry.path().stem().string().ends_with("_sweep")) {
      found.insert(entry.path().stem().string());
    }
  }
  EXPECT_EQ(found, std::set<std::string>(kExampleNames.begin(), kExampleNames.end()))
      << "a new example needs a place in kExampleNames, so it is run here";
}

class Example : public testing::TestWithParam<std::string> {};

TEST_P(Example, LoadsAndFitsItsTrajectory) {
  const Scenario scenario = load_scenario(example(GetParam()));
  EXPECT_EQ(scenario.name, GetParam());
  const LocalFrame frame(scenario.origin);
  const Trajectory trajectory = load_trajectory(scenario, frame);
  const double duration_s =
      scenario.trajectory.duration_s.value_or(trajectory.end_s() - scenario.trajectory.start_s);
  EXPECT_LE(scenario.trajectory.start_s + duration_s, trajectory.end_s() + 1e-9)
      << "`owsim run` without --duration must fit the trajectory";
  EXPECT_GE(duration_s, 15.0) << "an example flies long enough to see its objects";
  const Scene scene = build_scene(scenario);
  EXPECT_FALSE(scene.conductors.empty());
  EXPECT_NEAR(scenario.origin.lat_deg, 48.6881, 1e-9);
  EXPECT_NEAR(scenario.origin.lon_deg, 10.8447, 1e-9);
}

// Runs the example for 1 s (3 frames) and checks every file against the others.
TEST_P(Example, RunsIntoTheExpectedFiles) {
  const std::string name = GetParam();
  const TempDir dir("owsim_example_" + name);
  const CliResult run = run_cli(
      {"run", example(name).string(), "--out", "out", "--duration", "1", "--quiet"}, dir.path());
  ASSERT_EQ(run.exit_status, 0) << run.command << "\n" << run.err;
  EXPECT_EQ(run.err, "") << "--quiet";
  const fs::path out = dir / "out";
  constexpr int kFrames = 3;  // floor(1 s / 0.33304 s)

  // Exactly the outputs, no temporaries left: quicklook/ holds the map and the range image of
  // every 10th frame (frame 0 only here).
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), out).string());
  }
  // Plus the copies of the files the scenario names (scenario.yaml names them there), so the
  // folder reads only its own tree.
  std::set<std::string> expected{"flight.d64",        "points.csv",
                                 "points.las",        "points.ply",
                                 "trajectory.csv",    "summary.json",
                                 "truth.csv",         "scenario.yaml",
                                 "quicklook/map.png", "quicklook/frame_000000.png"};
  if (name == "hellsim_flight") expected.insert("inputs/1/hellsim_turn_north.txt");
  if (name == "real_corridor") {
    expected.insert({"inputs/1/real_corridor_dem.asc", "inputs/1/real_corridor_dem.prj",
                     "inputs/2/real_corridor_lines.geojson", "inputs/3/real_corridor_barn.obj"});
  }
  EXPECT_EQ(files, expected);
  for (const char* png : {"quicklook/map.png", "quicklook/frame_000000.png"}) {
    EXPECT_EQ(test::read_whole_file(out / png).substr(0, 8), "\x89PNG\r\n\x1a\n") << png;
  }

  EXPECT_EQ(fs::file_size(out / "flight.d64"),
            static_cast<std::uintmax_t>(kFrames) * kPulsesPerFrame * 8);

  const std::vector<std::string> points = lines_of(test::read_whole_file(out / "points.csv"));
  ASSERT_FALSE(points.empty());
  EXPECT_EQ(points.front(), kPointsHeader);
  const std::size_t rows = points.size() - 1;
  EXPECT_GT(rows, 10'000u) << "the ground alone gives thousands of returns a frame";
  std::size_t second_returns = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    std::size_t commas = 0, at = 0;
    for (; commas < 4 && at < points[i].size(); ++at) commas += points[i][at] == ',';
    second_returns += points[i].compare(at, 2, "2,") == 0;  // the `return` column
  }

  // LAS 1.4, point format 6: the header's count and the file's size agree with points.csv.
  const std::string las = test::read_whole_file(out / "points.las");
  ASSERT_GE(las.size(), 375u);
  EXPECT_EQ(las.substr(0, 4), "LASF");
  EXPECT_EQ(little_endian(las, 24, 1), 1u);
  EXPECT_EQ(little_endian(las, 25, 1), 4u);
  EXPECT_EQ(little_endian(las, 104, 1), 6u);
  EXPECT_EQ(little_endian(las, 247, 8), rows);
  EXPECT_EQ(las.size(), little_endian(las, 96, 4) + rows * little_endian(las, 105, 2));

  // PLY: the vertex count and the size its properties imply.
  const std::string ply = test::read_whole_file(out / "points.ply");
  const std::size_t header_end = ply.find("end_header\n");
  ASSERT_NE(header_end, std::string::npos);
  EXPECT_EQ(ply.substr(0, 36), "ply\nformat binary_little_endian 1.0\n");
  std::size_t vertices = 0, vertex_bytes = 0;
  const std::map<std::string, std::size_t> type_bytes = {
      {"double", 8}, {"float", 4}, {"uchar", 1}, {"int", 4}, {"uint", 4}, {"ushort", 2}};
  for (const std::string& line : lines_of(ply.substr(0, header_end))) {
    std::istringstream words(line);
    std::string keyword, type, what;
    words >> keyword;
    if (keyword == "element") words >> what >> vertices;
    if (keyword == "property") {
      words >> type;
      ASSERT_TRUE(type_bytes.contains(type)) << line;
      vertex_bytes += type_bytes.at(type);
    }
  }
  EXPECT_EQ(vertices, rows);
  EXPECT_EQ(ply.size(), header_end + std::strlen("end_header\n") + rows * vertex_bytes);

  const std::vector<std::string> trajectory =
      lines_of(test::read_whole_file(out / "trajectory.csv"));
  ASSERT_EQ(trajectory.size(), static_cast<std::size_t>(kFrames) + 1);
  EXPECT_EQ(trajectory.front(), kTrajectoryHeader);
  const Scenario scenario = load_scenario(example(name));
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_NEAR(std::stod(trajectory[static_cast<std::size_t>(f) + 1]),
                scenario.trajectory.start_s + f * kFrameS, 1e-9);
  }

  const nlohmann::json summary = nlohmann::json::parse(test::read_whole_file(out / "summary.json"));
  EXPECT_EQ(summary["scenario"], name);
  EXPECT_EQ(summary["seed"], scenario.seed);
  EXPECT_EQ(summary["frames"], kFrames);
  EXPECT_EQ(summary["pulses"], kFrames * kPulsesPerFrame);
  EXPECT_EQ(summary["pulses_per_frame"], kPulsesPerFrame);
  EXPECT_GE(summary["threads"].get<int>(), 1);
  EXPECT_FALSE(summary["version"].get<std::string>().empty());
  std::size_t returns = 0;
  for (const auto& [surface, count] : summary["returns"].items()) {
    returns += count.get<std::size_t>();
  }
  EXPECT_EQ(returns, rows);
  EXPECT_EQ(summary["second_returns"].get<std::size_t>(), second_returns);
  const Scene scene = build_scene(scenario);
  std::vector<std::string> ids;
  for (const Conductor& conductor : scene.conductors) ids.push_back(conductor.id);
  for (const Cylinder& cylinder : scene.cylinders) ids.push_back(cylinder.id);
  for (const MeshObject& mesh : scene.meshes) ids.push_back(mesh.id);
  ASSERT_EQ(summary["objects"].size(), ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(summary["objects"][i]["id"], ids[i]);
}

INSTANTIATE_TEST_SUITE_P(Bundled, Example, testing::ValuesIn(kExampleNames),
                         [](const testing::TestParamInfo<std::string>& example_name) {
                           return example_name.param;
                         });

// ---- what each example promises ----

TEST(Examples, PylonLineIsASeptLineBetweenPylonsAmongTrees) {
  const Scenario scenario = load_scenario(example("pylon_line"));
  EXPECT_EQ(scenario.scene.terrain.kind, TerrainKind::flat);
  ASSERT_GE(scenario.scene.spans.size(), 2u);
  for (const SpanSpec& span : scenario.scene.spans) EXPECT_EQ(span.offsets.size(), 7u) << span.id;
  const Scene scene = build_scene(scenario);
  EXPECT_EQ(count_of(scene, SurfaceClass::pole), 3u);  // one pylon per support, none doubled
  EXPECT_GE(count_of(scene, SurfaceClass::tree), 100u);
}

TEST(Examples, CorridorIsTwoKilometresOfLinesTreesAndPoles) {
  const Scenario scenario = load_scenario(example("corridor"));
  EXPECT_EQ(scenario.scene.terrain.kind, TerrainKind::flat);
  std::size_t multi_conductor_spans = 0;
  for (const SpanSpec& span : scenario.scene.spans)
    multi_conductor_spans += span.offsets.size() > 1;
  EXPECT_GE(multi_conductor_spans, 5u);
  const Scene scene = build_scene(scenario);
  double east_min = 1e9, east_max = -1e9;
  for (const Conductor& conductor : scene.conductors) {
    for (const Eigen::Vector3d& point : conductor.points_enu_m) {
      east_min = std::min(east_min, point.x());
      east_max = std::max(east_max, point.x());
    }
  }
  EXPECT_GE(east_max - east_min, 2000.0);
  EXPECT_GE(count_of(scene, SurfaceClass::tree), 200u);
  EXPECT_GE(count_of(scene, SurfaceClass::pole), 10u);
  // Every support stands once: no two poles at one place.
  for (std::size_t i = 0; i < scene.cylinders.size(); ++i) {
    if (scene.cylinders[i].surface != SurfaceClass::pole) continue;
    for (std::size_t j = i + 1; j < scene.cylinders.size(); ++j) {
      if (scene.cylinders[j].surface != SurfaceClass::pole) continue;
      EXPECT_GT((scene.cylinders[i].base_enu_m - scene.cylinders[j].base_enu_m).norm(), 1.0)
          << scene.cylinders[i].id << " and " << scene.cylinders[j].id;
    }
  }
}

const fs::path kHellsimFile = kExamples / "data" / "hellsim_turn_north.txt";

TEST(Examples, HellsimFlightTurnsThroughNorthNearTheOrigin) {
  const Scenario scenario = load_scenario(example("hellsim_flight"));
  ASSERT_EQ(scenario.trajectory.source, TrajectorySpec::Source::file);
  EXPECT_EQ(scenario.trajectory.format, "hellsim");
  EXPECT_EQ(fs::canonical(scenario.trajectory.file), fs::canonical(kHellsimFile));

  // The header line, then 15 columns a record (SENSOR-SPEC §5).
  const std::vector<std::string> lines = lines_of(test::read_whole_file(kHellsimFile));
  ASSERT_GT(lines.size(), 1u);
  EXPECT_EQ(lines.front(),
            "Pic # Time-Tag Heading Pitch Roll X-Vel Y-Vel Z-Vel N-Vel E-Vel D-Vel Veloc Latitude "
            "Long. Altitude");

  const std::vector<NavRecord> records =
      read_hellsim(kHellsimFile.string(), {scenario.trajectory.tick_s});
  ASSERT_EQ(records.size(), lines.size() - 1);
  const double duration_s = records.back().time_s - records.front().time_s;
  EXPECT_NEAR(duration_s, 60.0, 5.0);
  EXPECT_GE(static_cast<double>(records.size() - 1) / duration_s, 4.0) << "records per second";

  const LocalFrame frame(scenario.origin);
  const NavTrack track = to_local(records, frame);
  int crossings = 0;
  double path_m = 0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    const double before = records[i - 1].attitude.heading_deg;
    const double after = records[i].attitude.heading_deg;
    if (before > 300.0 && after < 60.0) ++crossings;
    EXPECT_GE(wrap_180_deg(after - before), 0.0) << "record " << i << ": the turn is to the right";
    path_m += (track.position_enu_m[i] - track.position_enu_m[i - 1]).head<2>().norm();
    EXPECT_LT(track.position_enu_m[i].head<2>().norm(), 2000.0) << "record " << i;
  }
  EXPECT_EQ(crossings, 1);
  EXPECT_NEAR(path_m / duration_s, 40.0, 1.0) << "m/s";
}

// The real corridor's data is what examples/data/make_real_corridor.py writes, and the example
// holds its two GIS lines' spans and towers on the DEM and the barn standing on it.
TEST(Examples, RealCorridorIsItsScriptsDataAsTwoGisLinesAndABarnOnADem) {
  const TempDir dir("owsim_real_corridor_script");
  fs::copy_file(kExamples / "data" / "make_real_corridor.py", dir / "make_real_corridor.py");
  const std::string command =
      std::string(OWSIM_PYTHON) + " " + (dir / "make_real_corridor.py").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (const char* file : {"real_corridor_dem.asc", "real_corridor_dem.prj",
                           "real_corridor_lines.geojson", "real_corridor_barn.obj"}) {
    EXPECT_EQ(test::read_whole_file(dir / file), test::read_whole_file(kExamples / "data" / file))
        << file;
  }
  const Scenario scenario = load_scenario(example("real_corridor"));
  EXPECT_EQ(scenario.scene.terrain.kind, TerrainKind::dem);
  EXPECT_EQ(scenario.scene.spans.size(), 5u + 8u);
  EXPECT_EQ(scenario.scene.spans.front().id, "hv/1");
  EXPECT_EQ(scenario.scene.spans.back().id, "mv/8");
  EXPECT_EQ(scenario.scene.poles.size(), 6u + 9u);
  const Scene scene = build_scene(scenario);
  EXPECT_EQ(scene.conductors.size(), 5u * 7u + 8u * 3u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const MeshObject& barn = scene.meshes.front();
  EXPECT_EQ(barn.id, "barn");
  EXPECT_EQ(barn.surface, SurfaceClass::building);
  EXPECT_EQ(barn.mesh.triangles.size(), 14u);
  // Its floor's middle (the model's origin) on the DEM, its ridge 13 m above.
  double floor = 1e9;
  double ridge = -1e9;
  for (const auto& vertex : barn.mesh.vertices) {
    floor = std::min(floor, vertex.z());
    ridge = std::max(ridge, vertex.z());
  }
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (const auto& vertex : barn.mesh.vertices) {
    if (vertex.z() == floor) middle += vertex / 4.0;  // the four floor corners
  }
  EXPECT_NEAR(middle.z(), scenario.scene.terrain.height_at(middle.x(), middle.y()), 1e-6);
  EXPECT_NEAR(ridge - floor, 13.0, 1e-9);
}

// The bundled file is what examples/data/make_hellsim_turn.py writes (every number to within
// its last printed digit, so a different libm cannot fail the comparison).
TEST(Examples, HellsimFileIsWhatItsScriptWrites) {
  const TempDir dir("owsim_hellsim_script");
  const fs::path written = dir / "turn.txt";
  const std::string command = std::string(OWSIM_PYTHON) + " " +
                              (kExamples / "data" / "make_hellsim_turn.py").string() + " " +
                              written.string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::vector<std::string> bundled = lines_of(test::read_whole_file(kHellsimFile));
  const std::vector<std::string> fresh = lines_of(test::read_whole_file(written));
  ASSERT_EQ(fresh.size(), bundled.size());
  ASSERT_FALSE(fresh.empty());
  EXPECT_EQ(fresh.front(), bundled.front());
  for (std::size_t i = 1; i < fresh.size(); ++i) {
    std::istringstream a(fresh[i]), b(bundled[i]);
    std::string x, y;
    int column = 0;
    while (b >> y) {
      ASSERT_TRUE(a >> x) << "line " << i + 1;
      const std::size_t dot = y.find('.');
      const double unit =
          dot == std::string::npos ? 1.0 : std::pow(10.0, -static_cast<double>(y.size() - dot - 1));
      EXPECT_NEAR(std::stod(x), std::stod(y), 1.5 * unit)
          << "line " << i + 1 << " column " << column;
      ++column;
    }
    EXPECT_FALSE(a >> x) << "line " << i + 1 << " has more columns";
    EXPECT_EQ(column, 15) << "line " << i + 1;
  }
}

}  // namespace
}  // namespace owsim
