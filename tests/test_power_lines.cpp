// Protects power lines from GIS files (scenario key scene.power_lines, io/scenario/gis_lines.hpp):
// a GeoJSON line of towers flies byte for byte like the same spans and tower poles written by
// hand at the towers' latitudes and longitudes (whose catenaries and poles other suites check
// against scipy), the names and overrides follow the rules, and bad files give one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "cli_runner.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

const std::string kHead = R"(name: lines
seed: 7
origin: {lat: 48.6881, lon: 10.8447, h: 450.0}
sensor: {model: milows, mount: {roll_deg: 0, pitch_deg: -4, yaw_deg: 0, lever_arm_m: [0, 0, 0]}}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: -600, n: 0, u: 70}, {e: 200, n: 0, u: 70}]
  duration_s: 12
)";

// Towers of a north–south line crossing the route, and of a short east–west one.
const char* kTowers[] = {"[10.8447, 48.6845]", "[10.8447, 48.68675]", "[10.84475, 48.6890]",
                         "[10.8447, 48.6912]"};

class PowerLines : public ::testing::Test {
 protected:
  CliResult run(const std::string& name, const std::string& scene) {
    const fs::path scenario = dir_ / (name + ".yaml");
    std::ofstream(scenario) << kHead << scene;
    return run_cli({"run", scenario.string(), "--frames", "30", "--outputs", "d64,summary", "--out",
                    (dir_ / name).string()},
                   dir_.path());
  }
  void write(const std::string& file, const std::string& text) {
    std::ofstream(dir_ / file) << text;
  }
  TempDir dir_{"owsim_power_lines"};
};

TEST_F(PowerLines, AGisLineFliesLikeTheSameSpansWrittenByHand) {
  std::string coordinates;
  for (const char* tower : kTowers)
    coordinates += std::string(coordinates.empty() ? "" : ", ") + tower;
  write("line.geojson",
        R"({"type": "FeatureCollection", "features": [{"type": "Feature",
            "properties": {"name": "ns", "lowest_point_m": 18},
            "geometry": {"type": "LineString", "coordinates": [)" +
            coordinates + "]}}]}");
  const CliResult gis = run("gis", R"(scene:
  terrain: {flat_u: 3}
  power_lines:
    - {file: line.geojson, support_heights_m: [28, 28], lowest_point_m: 25, layout: tri,
       conductor: {diameter_mm: 22}, supports: {kind: pole, diameter_m: 0.7}}
)");
  ASSERT_EQ(gis.exit_status, 0) << gis.err;
  std::string spans, poles;
  const auto at = [](const char* tower) {
    std::string t(tower);
    const auto comma = t.find(',');
    return "{lat: " + t.substr(comma + 2, t.size() - comma - 3) +
           ", lon: " + t.substr(1, comma - 1) + "}";
  };
  for (std::size_t k = 0; k < std::size(kTowers); ++k) {
    if (k + 1 < std::size(kTowers)) {
      spans += "    - {id: ns-" + std::to_string(k + 1) + ", from: " + at(kTowers[k]) +
               ", to: " + at(kTowers[k + 1]) +
               ", support_heights_m: [28, 28], lowest_point_m: 18, layout: tri, conductor: "
               "{diameter_mm: 22}, supports: {kind: none}}\n";
    }
    poles += "    - {id: tower-" + std::to_string(k + 1) + ", at: " + at(kTowers[k]) +
             ", height_m: 28, diameter_m: 0.7}\n";
  }
  const CliResult hand =
      run("hand", "scene:\n  terrain: {flat_u: 3}\n  spans:\n" + spans + "  poles:\n" + poles);
  ASSERT_EQ(hand.exit_status, 0) << hand.err;
  const std::string words = test::read_whole_file(dir_ / "gis/flight.d64");
  EXPECT_GT(words.size(), 0u);
  EXPECT_TRUE(words == test::read_whole_file(dir_ / "hand/flight.d64"));
  const std::string summary = test::read_whole_file(dir_ / "gis/summary.json");
  for (const char* id : {"\"ns/1/1\"", "\"ns/3/3\"", "\"ns/tower-4\""}) {
    EXPECT_NE(summary.find(id), std::string::npos) << id;
  }
  // The route crosses the line: its wires and towers are seen.
  const auto wires = summary.find("\"wire\": ", summary.find("\"returns\": {"));
  ASSERT_NE(wires, std::string::npos);
  EXPECT_GT(std::stol(summary.substr(wires + 8)), 100) << summary.substr(0, 600);
}

TEST_F(PowerLines, BadLinesGiveOneLineAndNoOutput) {
  write("one.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {}, "geometry": {"type": "LineString", "coordinates": [[10.8447, 48.6881]]}}]})");
  write("points.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {}, "geometry": {"type": "Point", "coordinates": [10.8447, 48.6881]}}]})");
  write("named.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {"name": "a/b"}, "geometry": {"type": "LineString",
      "coordinates": [[10.8447, 48.6845], [10.8447, 48.6912]]}}]})");
  write("two.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {}, "geometry": {"type": "LineString",
      "coordinates": [[10.8447, 48.6845], [10.8447, 48.6912]]}}]})");
  // Issue 33: a CRS PROJ does not know was read as WGS-84; a name that is not UTF-8 gave
  // nlohmann's internal message; a VRT names files anywhere.
  write("unknown_crs.geojson", R"({"type": "FeatureCollection",
      "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::999999"}},
      "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "LineString",
      "coordinates": [[10.8447, 48.6845], [10.8447, 48.6912]]}}]})");
  write("latin1.geojson",
        "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": "
        "\"Feature\", \"properties\": {\"name\": \"Stra\xdf" "e\"}, \"geometry\": "
        "{\"type\": \"LineString\", \"coordinates\": [[10.8447, 48.6845], "
        "[10.8447, 48.6912]]}}]}");
  // A name with a NUL character, which GDAL would cut short.
  write("nul.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {"name": "a\u0000b"}, "geometry": {"type": "LineString",
      "coordinates": [[10.8447, 48.6845], [10.8447, 48.6912]]}}]})");
  std::string towers;  // one tower more than owsim builds from a file
  for (int i = 0; i <= 100'000; ++i) {
    towers += (i ? "," : "") + std::string("[") + std::to_string(10.8 + i * 1e-6) + ",48.68]";
  }
  write("too_many.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature",
      "properties": {}, "geometry": {"type": "LineString", "coordinates": [)" +
                                towers + "]}}]}");
  write("lines.vrt",
        R"(<OGRVRTDataSource><OGRVRTLayer name="x"><SrcDataSource>/etc/passwd</SrcDataSource>
      </OGRVRTLayer></OGRVRTDataSource>)");
  const struct {
    std::string entry;
    std::string says;
  } cases[] = {{"{file: one.geojson}", "a line needs at least 2 towers, got 1"},
               {"{file: unknown_crs.geojson}", "layer 0: its CRS cannot be read"},
               {"{file: latin1.geojson}", "feature 0: property 'name' is not UTF-8 text"},
               {"{file: lines.vrt}", "which power_lines does not accept"},
               {"{file: nul.geojson}", "a NUL character (\\u0000), which GDAL would cut short"},
               {"{file: too_many.geojson}", "holds more than 100000 towers"},
               {"{file: 'http://127.0.0.1:9/lines.geojson'}", "a URL or a connection string"},
               {"{file: points.geojson}", "holds no LineString"},
               {"{file: missing.geojson}", "no such file: "},
               {"{file: named.geojson}", "property name must be non-empty and without '/'"},
               {"{file: two.geojson, support_heights_m: [20, 30]}", "share one height"}};
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.entry);
    const CliResult result =
        run("bad", "scene:\n  terrain: {flat_u: 0}\n  power_lines:\n    - " + bad.entry + "\n");
    EXPECT_NE(result.exit_status, 0);
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find("scene.power_lines"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.says), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad")) << result.err;
  }
}

}  // namespace
}  // namespace owsim
