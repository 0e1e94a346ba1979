// Protects triangle meshes (scenario key scene.meshes): the placement of a model in the local
// frame (geometry/mesh_placement.hpp) against pinned turns, the model files read through
// libowsim_mesh.so (OBJ polygons and PLY faces split into triangles), returns on an OBJ building
// and a y-up PLY tower placed by latitude and longitude lying on the meshes as an independent
// reader and pyproj place them (tests/oracles/mesh_oracle.py), the meshes as objects of the
// summary, and bad meshes giving one line and no output.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "geometry/mesh_placement.hpp"
#include "io/scenario/mesh_file.hpp"
#include "python_oracle.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::run_cli;
using test::TempDir;

void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  EXPECT_LT((actual - expected).norm(), 1e-12)
      << actual.transpose() << " vs " << expected.transpose();
}

TEST(MeshPlacement, YawTurnsClockwiseFromNorthLikeAHeading) {
  MeshPlacement placement;
  placement.yaw_deg = 90.0;
  expect_near(placed_vertex({0.0, 1.0, 0.0}, placement), {1.0, 0.0, 0.0});   // north → east
  expect_near(placed_vertex({1.0, 0.0, 0.0}, placement), {0.0, -1.0, 0.0});  // east → south
  expect_near(placed_vertex({0.0, 0.0, 1.0}, placement), {0.0, 0.0, 1.0});
  placement.yaw_deg = 30.0;
  expect_near(placed_vertex({0.0, 2.0, 0.0}, placement), {1.0, std::sqrt(3.0), 0.0});
}

TEST(MeshPlacement, YUpModelsStandUpAndScaleAndPositionFollow) {
  MeshPlacement placement;
  placement.up = ModelUpAxis::y;
  // Blender's OBJ export: up +y, forward −z, so the model's −z is north.
  expect_near(placed_vertex({0.0, 1.0, 0.0}, placement), {0.0, 0.0, 1.0});
  expect_near(placed_vertex({0.0, 0.0, -1.0}, placement), {0.0, 1.0, 0.0});
  expect_near(placed_vertex({1.0, 0.0, 0.0}, placement), {1.0, 0.0, 0.0});
  placement = MeshPlacement{};
  placement.at_enu_m = {10.0, 20.0, 30.0};
  placement.scale = 2.0;
  expect_near(placed_vertex({1.0, 1.0, 1.0}, placement), {12.0, 22.0, 32.0});
}

// Any placement is a rotation, a scaling and a shift: distances scale, turning sense is kept (a
// triangle's normal turns with the model, never flips), whatever the axis convention.
TEST(MeshPlacement, RandomPlacementsKeepShapeAndWinding) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  for (int i = 0; i < 500; ++i) {
    MeshPlacement placement;
    placement.yaw_deg = coordinate(rng) * 7.0;
    placement.scale = 0.1 + std::abs(coordinate(rng)) / 10.0;
    placement.up = i % 2 == 0 ? ModelUpAxis::z : ModelUpAxis::y;
    placement.at_enu_m = {coordinate(rng), coordinate(rng), coordinate(rng)};
    const Eigen::Vector3d a(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d b(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d c(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d pa = placed_vertex(a, placement);
    const Eigen::Vector3d pb = placed_vertex(b, placement);
    const Eigen::Vector3d pc = placed_vertex(c, placement);
    EXPECT_NEAR((pb - pa).norm(), placement.scale * (b - a).norm(), 1e-9);
    const double volume = (b - a).cross(c - a).dot(a - Eigen::Vector3d(1, 2, 3));
    const Eigen::Vector3d p0 = placed_vertex({1, 2, 3}, placement);
    const double placed_volume = (pb - pa).cross(pc - pa).dot(pa - p0);
    EXPECT_NEAR(placed_volume, std::pow(placement.scale, 3) * volume,
                1e-9 * std::max(1.0, std::abs(placed_volume)));
  }
}

// A 24 × 12 m barn with 8 m walls and a 13 m ridge: six quads and two triangles.
// Its ten corners, then its faces.
const std::string kBarnCorners = R"(v -12 -6 0
v 12 -6 0
v 12 6 0
v -12 6 0
v -12 -6 8
v 12 -6 8
v 12 6 8
v -12 6 8
v -12 0 13
v 12 0 13
)";
const std::string kBarnObj = "# barn\n" + kBarnCorners + R"(f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
f 5 6 10 9
f 7 8 9 10
f 6 7 10
f 8 5 9
)";

// A y-up pyramid (a stand-in lattice tower): a 4 × 4 base quad and four sides up to 10.
const char* kTowerPly = R"(ply
format ascii 1.0
element vertex 5
property float x
property float y
property float z
element face 5
property list uchar int vertex_indices
end_header
-2 0 -2
2 0 -2
2 0 2
-2 0 2
0 10 0
4 0 1 2 3
3 0 4 1
3 1 4 2
3 2 4 3
3 3 4 0
)";

class Meshes : public ::testing::Test {
 protected:
  void write(const std::string& file, const std::string& text) {
    std::ofstream(dir_ / file) << text;
  }
  CliResult run(const std::string& name, const std::string& meshes) {
    std::ofstream(dir_ / (name + ".yaml")) << "name: " << name << R"(
seed: 3
origin: {lat: 48.6881, lon: 10.8447, h: 450.0}
sensor: {model: milows, mount: {roll_deg: 0, pitch_deg: -4, yaw_deg: 0, lever_arm_m: [0, 0, 0]}}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: -600, n: 0, u: 70}, {e: 300, n: 0, u: 70}]
scene:
  terrain: {flat_u: 2}
  meshes:
)" << meshes;
    return run_cli({"run", (dir_ / (name + ".yaml")).string(), "--no-noise", "--frames", "40",
                    "--outputs", "points,summary", "--out", (dir_ / name).string()},
                   dir_.path());
  }
  // Models that name files outside their folder: an OBJ's material library on a device and out of
  // the folder, a glTF's buffer in /etc.
  void write_hostile_meshes() {
    const std::string triangle = "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n";
    write("mtl_device.obj", "mtllib /dev/zero\n" + triangle);
    write("mtl_above.obj", "mtllib ../above.mtl\n" + triangle);
    write("buffer_passwd.gltf",
          R"({"asset":{"version":"2.0"},"buffers":[{"uri":"/etc/passwd","byteLength":36}],)"
          R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],"accessors":[{)"
          R"("bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],)"
          R"("max":[1,1,1]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
          R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
    write("with_material.obj", "mtllib materials/wood.mtl\n" + triangle);
    fs::create_directories(dir_ / "materials");
    write("materials/wood.mtl", "newmtl wood\nKd 0.5 0.4 0.3\n");
  }

  TempDir dir_{"owsim_meshes"};
};

TEST_F(Meshes, FilesAreReadAsTriangles) {
  write("barn.obj", kBarnObj);
  write("tower.ply", kTowerPly);
  const TriangleMesh barn = read_mesh_file(dir_ / "barn.obj").mesh;
  EXPECT_EQ(barn.triangles.size(), 14u);
  double top = 0.0;
  for (const auto& vertex : barn.vertices) top = std::max(top, vertex.z());
  EXPECT_EQ(top, 13.0);
  const TriangleMesh tower = read_mesh_file(dir_ / "tower.ply").mesh;
  EXPECT_EQ(tower.triangles.size(), 6u);
  EXPECT_EQ(tower.vertices.size(), 5u);
}

// An OBJ is read by tinyobjloader, a PLY by assimp: the barn written both ways, with OBJ's
// v/vt/vn face syntax, negative (relative) indices and a polygon of five corners, is the same
// closed surface — the same area and enclosed volume (so the same winding), the same vertices.
TEST_F(Meshes, TheObjReaderAgreesWithAssimpOnTheSameSurface) {
  write("barn_faces.obj", kBarnCorners + R"(vt 0 0
vn 0 0 1
f 1/1/1 2/1/1 6/1/1 5/1/1
f 2//1 3//1 7//1 6//1
f -8 -7 -3 -4
f 4 1 5 8
f 5 6 10 9
f 7 8 9 10
f 6 7 10
f 8 5 9
)");
  write("barn.ply", R"(ply
format ascii 1.0
element vertex 10
property float x
property float y
property float z
element face 8
property list uchar int vertex_indices
end_header
-12 -6 0
12 -6 0
12 6 0
-12 6 0
-12 -6 8
12 -6 8
12 6 8
-12 6 8
-12 0 13
12 0 13
4 0 1 5 4
4 1 2 6 5
4 2 3 7 6
4 3 0 4 7
4 4 5 9 8
4 6 7 8 9
3 5 6 9
3 7 4 8
)");
  const auto area_and_volume = [](const TriangleMesh& mesh) {
    double area = 0.0, volume = 0.0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3d& a = mesh.vertices[t[0]];
      const Eigen::Vector3d& b = mesh.vertices[t[1]];
      const Eigen::Vector3d& c = mesh.vertices[t[2]];
      area += 0.5 * (b - a).cross(c - a).norm();
      volume += a.dot(b.cross(c)) / 6.0;
    }
    return std::pair{area, volume};
  };
  const TriangleMesh obj = read_mesh_file(dir_ / "barn_faces.obj").mesh;
  const TriangleMesh ply = read_mesh_file(dir_ / "barn.ply").mesh;
  EXPECT_EQ(obj.triangles.size(), 14u);
  EXPECT_EQ(ply.triangles.size(), 14u);
  const auto [obj_area, obj_volume] = area_and_volume(obj);
  const auto [ply_area, ply_volume] = area_and_volume(ply);
  EXPECT_NEAR(obj_area, ply_area, 1e-9);
  // Walls 2·(24·8) + 2·(12·8), roof 2·(24·√61), gables 2·(½·12·5).
  EXPECT_NEAR(obj_area, 2 * 24 * 8 + 2 * 12 * 8 + 2 * 24 * std::sqrt(61.0) + 2 * 0.5 * 12 * 5,
              1e-9);
  EXPECT_NEAR(obj_volume, ply_volume, 1e-9);
  EXPECT_NEAR(std::abs(obj_volume), 24 * 12 * 8 + 0.5 * 12 * 5 * 24, 1e-9);
  std::vector<std::array<double, 3>> obj_points, ply_points;
  for (const auto& v : obj.vertices) obj_points.push_back({v.x(), v.y(), v.z()});
  for (const auto& v : ply.vertices) ply_points.push_back({v.x(), v.y(), v.z()});
  std::sort(obj_points.begin(), obj_points.end());
  std::sort(ply_points.begin(), ply_points.end());
  EXPECT_EQ(obj_points, ply_points);
}

TEST_F(Meshes, ReturnsLieOnTheMeshesAndEachMeshIsAnObject) {
  write("barn.obj", kBarnObj);
  write("tower.ply", kTowerPly);
  // The tower by latitude and longitude: about 280 m east, 40 m south of the origin.
  const CliResult result = run(
      "two",
      R"(    - {id: barn, file: barn.obj, at: {e: 150, n: 35, u: 2}, yaw_deg: 30, reflectivity: 0.3}
    - {id: tower, file: tower.ply, at: {lat: 48.68774, lon: 10.84850, h: 452.5}, yaw_deg: -20,
       scale: 2, up_axis: y, class: pole, reflectivity: 0.2}
)");
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const nlohmann::json spec = {{"origin", {48.6881, 10.8447, 450.0}},
                               {"meshes",
                                {{{"id", "barn"},
                                  {"file", "barn.obj"},
                                  {"at", {{"e", 150}, {"n", 35}, {"u", 2}}},
                                  {"yaw_deg", 30}},
                                 {{"id", "tower"},
                                  {"file", "tower.ply"},
                                  {"at", {{"lat", 48.68774}, {"lon", 10.84850}, {"h", 452.5}}},
                                  {"yaw_deg", -20},
                                  {"scale", 2},
                                  {"up_axis", "y"}}}}};
  std::ofstream(dir_ / "spec.json") << spec.dump();
  const std::string verdict = test::run_python_file(
      fs::path(OWSIM_SOURCE_DIR) / "tests/oracles/mesh_oracle.py",
      {(dir_ / "spec.json").string() + " " + (dir_ / "two/points.csv").string(), false});
  ASSERT_EQ(verdict.rfind("ok ", 0), 0u) << verdict;
  int barn = 0, tower = 0;
  ASSERT_EQ(std::sscanf(verdict.c_str(), "ok barn=%d tower=%d", &barn, &tower), 2) << verdict;
  EXPECT_GT(barn, 1000) << verdict;
  EXPECT_GT(tower, 100) << verdict;

  std::ifstream file(dir_ / "two/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(file);
  EXPECT_EQ(summary["returns"]["building"], barn);
  EXPECT_EQ(summary["objects_by_class"]["building"]["objects"], 1);
  const auto& objects = summary["objects"];
  const auto entry = [&](const std::string& id) {
    return *std::find_if(objects.begin(), objects.end(),
                         [&](const nlohmann::json& o) { return o["id"] == id; });
  };
  EXPECT_EQ(entry("barn")["class"], "building");
  EXPECT_EQ(entry("barn")["returns"], barn);
  EXPECT_EQ(entry("tower")["class"], "pole");
  EXPECT_EQ(entry("tower")["returns"], tower);
}

// At the seam: the mesh module opens nothing outside the model's folder tree, whoever calls it,
// and says what else it read (a run folder copies those with the model).
TEST_F(Meshes, AModelReadsOnlyFilesBesideOrBelowIt) {
  write_hostile_meshes();
  for (const char* model : {"mtl_device.obj", "mtl_above.obj", "buffer_passwd.gltf"}) {
    SCOPED_TRACE(model);
    try {
      (void)read_mesh_file(dir_ / model);
      FAIL() << "read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("the mesh refers to"), std::string::npos) << e.what();
    }
  }
  const MeshFile read = read_mesh_file(dir_ / "with_material.obj");
  EXPECT_EQ(read.mesh.triangles.size(), 1u);
  EXPECT_EQ(read.companions, std::vector<fs::path>{fs::canonical(dir_ / "materials/wood.mtl")});
}

TEST_F(Meshes, BadMeshesGiveOneLineAndNoOutput) {
  write("barn.obj", kBarnObj);
  write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n");
  write("garbage.ply", "ply\nformat ascii 1.0\nelement vertex two\nend_header\n");
  write_hostile_meshes();
  fs::create_symlink("/dev/zero", dir_ / "zero.obj");
  write("huge_faces.ply",
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 4000000000\n"
        "property list uchar int vertex_indices\nend_header\n");
  write("odd_format.ply", "ply\nformat ascii 2.0\nelement vertex 0\nend_header\n");
  // Found by fuzz_scene_files: assimp leaks on a property of an unknown type.
  write("odd_property.ply",
        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar iices\nend_header\n3 0 1 2\n");
  // Found by fuzz_scene_files: a count beyond any integer was converted to one (undefined).
  write("beyond_faces.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1e55\nproperty list uchar int vertex_indices\n"
        "end_header\n");
  // Found by fuzz_scene_files: assimp loops forever on a format line holding other bytes.
  using namespace std::string_literals;  // the literal holds a NUL byte
  write("bad_format.ply", "ply\nformat ascii\0\xff\xff 1.0\nelement vertex 0\nend_header\n"s);
  const struct {
    std::string entry;
    std::string says;
  } cases[] = {
      {"{id: m, file: missing.obj, at: {e: 0, n: 0}}", "file: no such file: "},
      {"{id: m, file: points.obj, at: {e: 0, n: 0}}", "points.obj: "},
      {"{id: m, file: lines.obj, at: {e: 0, n: 0}}", "lines.obj: the mesh has no triangles"},
      {"{id: m, file: garbage.ply, at: {e: 0, n: 0}}",
       "garbage.ply: line 3 of its PLY header is not 'element NAME COUNT'"},
      {"{id: m, file: barn.obj, at: {e: 0, n: 0}, class: wire}", "class"},
      {"{id: m, file: barn.obj, at: {e: 0, n: 0}, scale: 0}", "scale"},
      {"{id: m, file: barn.obj, at: {e: 0, n: 0}, up_axis: x}", "up_axis"},
      // Issue 33: the mesh file and what it names stay in the scenario's folder tree.
      {"{id: m, file: /etc/passwd, at: {e: 0, n: 0}}", "outside the folder"},
      {"{id: m, file: zero.obj, at: {e: 0, n: 0}}", "outside the folder"},
      {"{id: m, file: mtl_device.obj, at: {e: 0, n: 0}}", "the mesh refers to"},
      {"{id: m, file: buffer_passwd.gltf, at: {e: 0, n: 0}}", "the mesh refers to"},
      // A header claiming 4·10⁹ faces in a few hundred bytes ran out of memory in assimp.
      {"{id: m, file: huge_faces.ply, at: {e: 0, n: 0}}",
       "the PLY header claims 3 vertex, 4000000000 face, more than its 178 bytes can hold"},
      {"{id: m, file: bad_format.ply, at: {e: 0, n: 0}}",
       "line 2 of its PLY header holds bytes that are not text"},
      {"{id: m, file: odd_format.ply, at: {e: 0, n: 0}}", "its PLY format line is not"},
      {"{id: m, file: beyond_faces.ply, at: {e: 0, n: 0}}",
       "line 7 of its PLY header is not 'element NAME COUNT'"},
      {"{id: m, file: odd_property.ply, at: {e: 0, n: 0}}",
       "line 4 of its PLY header is not a property of a PLY type"},
  };
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.entry);
    const CliResult result = run("bad", "    - " + bad.entry + "\n");
    EXPECT_NE(result.exit_status, 0);
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find("scene.meshes[0]"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.says), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
}

}  // namespace
}  // namespace owsim
