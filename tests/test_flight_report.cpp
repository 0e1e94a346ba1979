// `owsim view`'s page data (io/report/, owsim/flight_report.hpp): range-image cells placed as the
// quick-look lays them out, marks by class priority, evenly spread frames; the 3D cloud's class
// budgets and quantisation bound; the readers' errors; and a whole page read back — its meta
// JSON and both blobs inflated with zlib independently of the writer.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "io/report/flight_folder.hpp"
#include "io/report/report_cloud.hpp"
#include "io/report/report_frames.hpp"
#include "io/report/report_page.hpp"
#include "io/report/report_points.hpp"
#include "io/report/report_summary.hpp"
#include "io/report/report_trajectory.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "owsim/flight_report.hpp"
#include "sensor/fiber_layout.hpp"

namespace owsim {
namespace {

using test::TempDir;

void add_return(ReportPoints& p, int frame, int line, int fiber, int ret, float range,
                SurfaceClass surface, float e = 0, float n = 0, float u = 0) {
  p.e_m.push_back(e);
  p.n_m.push_back(n);
  p.u_m.push_back(u);
  p.range_m.push_back(range);
  p.surface.push_back(static_cast<std::uint8_t>(surface));
  p.frame.push_back(frame);
  p.line.push_back(static_cast<std::int16_t>(line));
  p.fiber.push_back(static_cast<std::int16_t>(fiber));
  p.return_number.push_back(static_cast<std::uint8_t>(ret));
  p.pulses_known = true;
}

std::uint16_t cell_range(const ReportFrames& f, std::size_t slot, std::size_t cells,
                         std::size_t c) {
  const std::uint8_t* plane = f.planes.data() + slot * 3 * cells;
  return static_cast<std::uint16_t>(plane[2 * c] | (plane[2 * c + 1] << 8));
}
std::uint8_t cell_mark(const ReportFrames& f, std::size_t slot, std::size_t cells, std::size_t c) {
  return f.planes[slot * 3 * cells + 2 * cells + c];
}

TEST(ReportFrames, CellsFollowTheQuicklookLayout) {
  const ScanParams scan;
  const RangeImageLayout layout = range_image_layout(scan);
  ASSERT_EQ(layout.fibers.size(), 127u);
  EXPECT_EQ(layout.lines, 159);
  EXPECT_DOUBLE_EQ(layout.beta_first_deg, -18.0);
  EXPECT_DOUBLE_EQ(layout.alpha_deg.front(), fiber_alpha_deg(scan, layout.fibers.front()));
  const std::size_t cells = 127 * 159;
  ReportPoints p;
  // Frame 0 sweeps up: line 3 is column 3. Fiber 65 is the top row (highest α).
  add_return(p, 0, 3, 65, 1, 123.44f, SurfaceClass::tree);
  add_return(p, 0, 3, 65, 2, 300.0f, SurfaceClass::wire);  // behind the tree: still marked wire
  // Frame 1 sweeps down: line 3 is column 158 − 3; fiber 1 is the bottom row.
  add_return(p, 1, 3, 1, 1, 50.0f, SurfaceClass::ground);
  add_return(p, 1, 4, 1, 1, 60.0f, SurfaceClass::fog);
  add_return(p, 1, 4, 1, 2, 61.0f, SurfaceClass::pole);
  add_return(p, 1, 5, 128, 1, 61.0f, SurfaceClass::pole);  // the reference fiber: no row
  const ReportFrames f = report_frames(p, layout, 0, 10);
  ASSERT_EQ(f.frames_total, 2);
  ASSERT_EQ(f.frames, (std::vector<std::int64_t>{0, 1}));
  EXPECT_EQ(f.returns_outside, 1u);
  EXPECT_EQ(cell_range(f, 0, cells, 3), 1234);  // decimetres of the first return
  EXPECT_EQ(cell_mark(f, 0, cells, 3), 1 + static_cast<int>(SurfaceClass::wire));
  const std::size_t bottom = 126 * 159;
  EXPECT_EQ(cell_range(f, 1, cells, bottom + 155), 500);
  EXPECT_EQ(cell_mark(f, 1, cells, bottom + 155), 0);  // ground is not marked
  EXPECT_EQ(cell_mark(f, 1, cells, bottom + 154), 1 + static_cast<int>(SurfaceClass::pole));
  EXPECT_EQ(cell_range(f, 1, cells, 0), 0);  // no return
}

TEST(ReportFrames, AFalseFirstReturnIsMarkedNoiseUnlessAWirePoleTreeOrFogIs) {
  const std::size_t cells = 127 * 159;
  ReportPoints p;
  // Frame 0, top row (fiber 65): line 10 a false return alone; line 11 a false return, a wire
  // behind; line 12 ground, a false return behind.
  add_return(p, 0, 10, 65, 1, 700.0f, SurfaceClass::noise);
  add_return(p, 0, 11, 65, 1, 90.0f, SurfaceClass::noise);
  add_return(p, 0, 11, 65, 2, 300.0f, SurfaceClass::wire);
  add_return(p, 0, 12, 65, 1, 150.0f, SurfaceClass::ground);
  add_return(p, 0, 12, 65, 2, 900.0f, SurfaceClass::noise);
  const ReportFrames f = report_frames(p, range_image_layout(ScanParams{}), 0, 10);
  EXPECT_EQ(cell_mark(f, 0, cells, 10), 1 + static_cast<int>(SurfaceClass::noise));
  EXPECT_EQ(cell_range(f, 0, cells, 10), 7000);
  EXPECT_EQ(cell_mark(f, 0, cells, 11), 1 + static_cast<int>(SurfaceClass::wire));
  EXPECT_EQ(cell_mark(f, 0, cells, 12), 0);
  EXPECT_EQ(cell_range(f, 0, cells, 12), 1500);
}

TEST(ReportFrames, LongFlightsShowEvenlySpreadFrames) {
  ReportPoints p;
  add_return(p, 9, 0, 1, 1, 10.0f, SurfaceClass::ground);
  const ReportFrames f = report_frames(p, range_image_layout(ScanParams{}), 0, 4);
  EXPECT_EQ(f.frames, (std::vector<std::int64_t>{0, 2, 5, 7}));
  EXPECT_EQ(report_frames(p, range_image_layout(ScanParams{}), 100, 4).frames_total, 100);
  EXPECT_THROW((void)report_frames(p, range_image_layout(ScanParams{}), 0, 0), Error);
}

TEST(ReportCloud, RareClassesStayWholeAndPositionsKeepTheirBound) {
  ReportPoints p;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> x(-1500.0f, 2500.0f), z(300.0f, 420.0f);
  for (int i = 0; i < 5000; ++i)
    add_return(p, 0, 0, 1, 1, 500.0f, SurfaceClass::ground, x(random), x(random), z(random));
  for (int i = 0; i < 40; ++i)
    add_return(p, 0, 0, 1, 1, 250.0f, SurfaceClass::wire, x(random), x(random), z(random));
  const ReportCloud all = report_cloud(p, 1'000'000);
  ASSERT_EQ(all.shown(), 5040u);
  for (std::size_t i = 0; i < all.shown(); ++i) {
    const float* axes[3] = {&p.e_m[i], &p.n_m[i], &p.u_m[i]};
    for (int a = 0; a < 3; ++a) {
      const double step = (all.box_max[a] - all.box_min[a]) / 65535.0;
      const double back = all.box_min[a] + all.xyz[3 * i + a] * step;
      EXPECT_LE(std::abs(back - *axes[a]), step / 2 + 1e-6 * std::abs(*axes[a])) << i << " " << a;
    }
  }
  const ReportCloud thin = report_cloud(p, 1040);
  EXPECT_EQ(thin.total, 5040u);
  EXPECT_EQ(thin.shown_by_class[static_cast<std::size_t>(SurfaceClass::wire)], 40u);
  EXPECT_EQ(thin.shown_by_class[static_cast<std::size_t>(SurfaceClass::ground)], 1000u);
  EXPECT_EQ(thin.shown(), 1040u);
  EXPECT_EQ(thin.range_dm.front(), 5000);
}

TEST(ReportPointsCsv, ReadsColumnsByNameAndNamesBadCells) {
  const TempDir dir;
  const auto write = [&](const std::string& text) {
    std::ofstream(dir / "points.csv") << text;
    return dir / "points.csv";
  };
  const std::string header =
      "frame,pulse,line,fiber,return,time_s,range_m,counter,e_m,n_m,u_m,"
      "lat_deg,lon_deg,h_m,class,object,energy_rel,incidence_deg\n";
  const ReportPoints p = read_report_points_csv(
      write(header +
            "2,5,0,6,1,0.5,214.8,358,-1156.7,-117.6,-0.05,48.6,10.8,450.0,wire,\"a,b\",0.02,65\n"
            "2,6,0,7,2,0.25,100.0,358,1,2,3,48.6,10.8,450.0,unknown,,,\n"));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_TRUE(p.pulses_known);
  EXPECT_FLOAT_EQ(p.e_m[0], -1156.7f);
  EXPECT_FLOAT_EQ(p.range_m[0], 214.8f);
  EXPECT_EQ(p.surface[0], static_cast<std::uint8_t>(SurfaceClass::wire));
  EXPECT_EQ(p.surface[1], kUnknownSurface);
  EXPECT_EQ(p.return_number[1], 2);
  EXPECT_EQ(p.frame_first_time_s.size(), 1u);
  EXPECT_DOUBLE_EQ(p.frame_first_time_s.at(2), 0.25);
  const auto message = [&](const std::string& text) {
    try {
      (void)read_report_points_csv(write(text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("frame,e_m,n_m\n"),
            (dir / "points.csv").string() +
                ":1: no column u_m "
                "(points.csv of owsim run or owsim decode has e_m, n_m, u_m)");
  EXPECT_EQ(message("e_m,n_m,u_m,range_m\n1,2,3,4\n1,2,3,x\n"),
            (dir / "points.csv").string() + ":3: range_m: 'x' is not a number");
  EXPECT_EQ(message("e_m,n_m,u_m,class\n1,2,3,cable\n"),
            (dir / "points.csv").string() + ":2: class: 'cable' is not a class");
}

TEST(FlightFolder, RefusesAFolderThatIsNoOwsimOutput) {
  const TempDir dir;
  std::ofstream(dir / "notes.txt") << "hello";
  try {
    (void)find_flight_folder(dir.path());
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an owsim output folder"), std::string::npos);
  }
  EXPECT_THROW((void)find_flight_folder(dir / "missing"), FileError);
}

// Base64 and inflate written here from the RFCs with zlib's uncompress, not the writer's code.
std::vector<std::uint8_t> unpack_blob(const std::string& text, std::size_t size) {
  std::vector<std::uint8_t> packed;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    if (c >= '0' && c <= '9') v = c - '0' + 52;
    if (c == '+') v = 62;
    if (c == '/') v = 63;
    if (v < 0) continue;
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    if ((count += 6) >= 8) {
      count -= 8;
      packed.push_back(static_cast<std::uint8_t>(bits >> count));
    }
  }
  std::vector<std::uint8_t> out(size);
  uLongf got = size;
  EXPECT_EQ(uncompress(out.data(), &got, packed.data(), static_cast<uLong>(packed.size())), Z_OK);
  EXPECT_EQ(got, size);
  return out;
}

std::string element(const std::string& html, const std::string& id) {
  const std::string open = "id=\"" + id + "\">";
  const std::size_t start = html.find(open);
  if (start == std::string::npos) return {};
  const std::size_t from = start + open.size();
  return html.substr(from, html.find("</script>", from) - from);
}

TEST(FlightReport, ThePageCarriesTheFolderAndSaysWhatItLeavesOut) {
  const TempDir dir;
  std::ofstream(dir / "summary.json")
      << R"({"scenario": "tiny</script>", "frames": 3, "objects": [)"
         R"({"id": "b", "first_seen_s": 2.0}, {"id": "never", "first_seen_s": null},)"
         R"({"id": "a", "first_seen_s": 1.0}]})";
  std::ofstream(dir / "trajectory.csv")
      << "time_s,lat_deg,lon_deg,h_m,e_m,n_m,u_m,roll_deg,pitch_deg,heading_deg\n"
         "0.0,48,10,400,1,2,100,0,0,90\n0.33,48,10,400,11,2,100,1,2,91\n";
  std::ofstream(dir / "points.csv") << "frame,line,fiber,return,time_s,range_m,e_m,n_m,u_m,class\n"
                                       "0,0,65,1,0.01,200.0,10,20,30,wire\n"
                                       "1,2,1,1,0.34,300.0,40,50,60,ground\n";
  FlightReportOptions options;
  options.max_objects = 2;
  const FlightReport report = write_flight_report(dir.path(), options);
  EXPECT_EQ(report.file, dir / "report.html");
  EXPECT_EQ(report.points_total, 2u);
  EXPECT_EQ(report.frames_total, 3);
  const std::string html = test::read_whole_file(report.file);
  EXPECT_EQ(html.size(), report.bytes);
  EXPECT_NE(html.find("<title>owsim — tiny&lt;/script&gt;</title>"), std::string::npos);
  const nlohmann::json meta = nlohmann::json::parse(element(html, "owsim-meta"));
  EXPECT_EQ(meta["title"], "tiny</script>");
  ASSERT_EQ(meta["objects"].size(), 2u);
  EXPECT_EQ(meta["objects"][0]["id"], "a");  // first seen first
  EXPECT_EQ(meta["objects"][1]["id"], "b");
  EXPECT_EQ(meta["objects_total"], 3);
  EXPECT_EQ(meta["frames"]["shown"], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(meta["frames"]["pose"][1][0], 11.0);
  EXPECT_TRUE(meta["frames"]["pose"][2].is_null());  // no trajectory row: no pose
  EXPECT_EQ(meta["cloud"]["by_class"]["wire"]["shown"], 1);
  const std::string notes = meta["notes"].dump();
  EXPECT_NE(notes.find("first 2 of 3 objects"), std::string::npos) << notes;
  EXPECT_NE(notes.find("--scenario FILE"), std::string::npos) << notes;

  const std::size_t cells = 127 * 159;
  const std::vector<std::uint8_t> planes =
      unpack_blob(element(html, "owsim-frames"), 3 * 3 * cells);
  EXPECT_EQ(planes[0] | (planes[1] << 8), 2000);  // frame 0, top row (fiber 65), column 0
  EXPECT_EQ(planes[2 * cells], 1 + static_cast<int>(SurfaceClass::wire));
  const std::vector<std::uint8_t> cloud = unpack_blob(element(html, "owsim-cloud"), 2 * 9);
  // Point 1 is the box's far corner: 65535 on every axis; ranges 2000 and 3000 dm; classes.
  EXPECT_EQ(cloud[6] | (cloud[7] << 8), 65535);
  EXPECT_EQ(cloud[12] | (cloud[13] << 8), 2000);
  EXPECT_EQ(cloud[16], static_cast<int>(SurfaceClass::wire));
  EXPECT_EQ(cloud[17], static_cast<int>(SurfaceClass::ground));
}

// summary.json's objects are judged as they stream past: the first seen first, the unseen after in
// file order, at most max_objects kept; the facts stay whole.
TEST(ReportSummary, KeepsTheFirstSeenRowsOfAStream) {
  const TempDir dir;
  std::ofstream(dir / "summary.json")
      << R"({"frames": 7, "objects_by_class": {"tree": {"objects": 4}}, "objects": [)"
         R"({"id": "u1", "first_seen_s": null}, {"id": "s2", "first_seen_s": 5.0},)"
         R"({"id": "u3"}, {"id": "s4", "first_seen_s": 1.0}], "version": "x"})";
  const ReportSummary three = read_report_summary(dir / "summary.json", 3);
  EXPECT_EQ(three.objects_total, 4u);
  ASSERT_EQ(three.objects.size(), 3u);
  EXPECT_EQ(three.objects[0]["id"], "s4");
  EXPECT_EQ(three.objects[1]["id"], "s2");
  EXPECT_EQ(three.objects[2]["id"], "u1");
  EXPECT_EQ(three.facts["frames"], 7);
  EXPECT_EQ(three.facts["objects_by_class"]["tree"]["objects"], 4);
  EXPECT_EQ(three.facts["version"], "x");
  EXPECT_FALSE(three.facts.contains("objects"));
  EXPECT_EQ(read_report_summary(dir / "summary.json", 0).objects.size(), 0u);
}

TEST(FlightReport, BadFilesNameThemselvesAndLeaveNoPage) {
  const TempDir dir;
  std::ofstream(dir / "summary.json") << "{\"frames\": ";
  try {
    (void)write_flight_report(dir.path());
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind((dir / "summary.json").string() + ": not JSON", 0), 0u)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "report.html"));
}

}  // namespace
}  // namespace owsim

namespace owsim {
namespace {

// points.las (and points.ply) read back: LAS through the zone's inverse projection lands where
// points.csv puts the same returns in the scenario's frame: with the scenario's origin, and with
// the origin that trajectory.csv implies (origin_of_frame).
TEST(ReportPointsLas, LandsOnTheCsvPositions) {
  const TempDir dir;
  const std::filesystem::path scenario =
      std::filesystem::path(OWSIM_SOURCE_DIR) / "examples" / "single_span.yaml";
  const test::CliResult run =
      test::run_cli({"run", scenario.string(), "--out", (dir / "out").string(), "--frames", "12",
                     "--outputs", "csv,las,ply,trajectory", "--quiet"},
                    dir.path());
  ASSERT_EQ(run.exit_status, 0) << run.err;
  const ReportPoints csv = read_report_points_csv(dir / "out/points.csv");
  ASSERT_GT(csv.size(), 100u);
  const ReportTrajectory trajectory = read_report_trajectory(dir / "out/trajectory.csv");
  const TrajectoryRow& row = trajectory.rows.front();
  const Geodetic implied =
      origin_of_frame({row.lat_deg, row.lon_deg, row.h_m}, {row.e_m, row.n_m, row.u_m});
  for (const Geodetic& origin : {load_scenario(scenario).origin, implied}) {
    const ReportPoints las = read_report_points_las(dir / "out/points.las", origin);
    ASSERT_EQ(las.size(), csv.size());
    double worst = 0;
    for (std::size_t i = 0; i < las.size(); ++i) {
      worst = std::max({worst, std::abs(double{las.e_m[i]} - csv.e_m[i]),
                        std::abs(double{las.n_m[i]} - csv.n_m[i]),
                        std::abs(double{las.u_m[i]} - csv.u_m[i])});
      ASSERT_EQ(las.surface[i], csv.surface[i]) << i;
    }
    // LAS keeps 0.1 mm, the CSV 0.1 mm; floats hold ~0.1 mm at a kilometre.
    EXPECT_LT(worst, 0.002);
  }
  // points.ply holds the same positions (float64) and classes.
  const ReportPoints ply = read_report_points_ply(dir / "out/points.ply");
  ASSERT_EQ(ply.size(), csv.size());
  for (std::size_t i = 0; i < ply.size(); ++i) {
    ASSERT_NEAR(ply.e_m[i], csv.e_m[i], 1e-3) << i;
    ASSERT_NEAR(ply.u_m[i], csv.u_m[i], 1e-3) << i;
    ASSERT_EQ(ply.surface[i], csv.surface[i]) << i;
  }
  std::ofstream(dir / "out/points.ply", std::ios::app) << "x";  // one byte too many
  EXPECT_THROW((void)read_report_points_ply(dir / "out/points.ply"), Error);

  // Without trajectory.csv (a decode folder) the page takes the poses from the scenario's
  // trajectory at each frame start: the run's own trajectory.csv rows, to its printed decimals.
  std::filesystem::rename(dir / "out/trajectory.csv", dir / "trajectory.csv");
  std::filesystem::remove(dir / "out/points.ply");
  FlightReportOptions options;
  options.scenario = scenario;
  const FlightReport page = write_flight_report(dir / "out", options);
  const nlohmann::json meta =
      nlohmann::json::parse(element(test::read_whole_file(page.file), "owsim-meta"));
  const ReportTrajectory written = read_report_trajectory(dir / "trajectory.csv");
  ASSERT_EQ(meta["frames"]["pose"].size(), 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    const nlohmann::json& pose = meta["frames"]["pose"][k];
    const TrajectoryRow& row = written.rows[k];
    EXPECT_NEAR(pose[0].get<double>(), row.e_m, 1e-4) << k;
    EXPECT_NEAR(pose[1].get<double>(), row.n_m, 1e-4) << k;
    EXPECT_NEAR(pose[2].get<double>(), row.u_m, 1e-4) << k;
    EXPECT_NEAR(pose[5].get<double>(), row.heading_deg, 1e-4) << k;
    EXPECT_NEAR(meta["frames"]["time_s"][k].get<double>(), row.time_s, 1e-9) << k;
  }
}

// Regression (issue 45): a crafted points.ply whose vertex count times 29 bytes wraps around 2^64
// to the bytes the file holds passed the size check, and `owsim view` ended in an internal error
// (std::bad_alloc reserving for the count). The count is now compared with the file's size by
// division, and the header must be owsim's layout line by line.
TEST(ReportPointsPly, CountsThatDoNotFitTheFileAreRefusedInOneLine) {
  const TempDir dir;
  const std::filesystem::path run = dir / "run";
  const test::CliResult flown = test::run_cli(
      {"run", (std::filesystem::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml").string(),
       "--out", run.string(), "--frames", "2", "--outputs", "ply,summary", "--quiet"},
      dir.path());
  ASSERT_EQ(flown.exit_status, 0) << flown.err;
  const std::string layout =
      "property double x\nproperty double y\nproperty double z\nproperty float intensity\n"
      "property uchar class\nend_header\n";
  const std::string start = "ply\nformat binary_little_endian 1.0\ncomment crafted\n";
  // 29 is odd, so it has an inverse modulo 2^64 (Newton's iteration doubles the good bits).
  std::uint64_t inverse = 29;
  for (int i = 0; i < 6; ++i) inverse *= 2 - 29 * inverse;
  const std::uint64_t wrapping = 10 * inverse;  // × 29 = 10 (mod 2^64)
  ASSERT_EQ(wrapping * 29, 10u);
  ASSERT_GT(wrapping, std::uint64_t{1} << 59);
  const auto message = [&](const std::string& bytes) {
    std::ofstream(run / "points.ply", std::ios::binary) << bytes;
    try {
      (void)read_report_points_ply(run / "points.ply");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string ply = (run / "points.ply").string();
  const std::string ten(10, '\0');
  EXPECT_EQ(message(start + "element vertex " + std::to_string(wrapping) + "\n" + layout + ten),
            ply + ": holds 10 bytes after its header, which says " + std::to_string(wrapping) +
                " vertices of 29 bytes");
  const std::string not_owsim =
      ply +
      ": not the PLY layout owsim writes (binary little-endian double x y z, float intensity, "
      "uchar class)";
  EXPECT_EQ(message(start + "element vertex 99999999999999999999999\n" + layout), not_owsim);
  EXPECT_EQ(message(start + "element vertex +1\n" + layout + std::string(29, '\0')), not_owsim);
  EXPECT_EQ(message(start + "element vertex 1\nelement face 0\n" + layout + std::string(29, '\0')),
            not_owsim);
  EXPECT_EQ(message(start + std::string(100'000, 'x')), not_owsim);  // no header in 64 KiB
  EXPECT_EQ(message(start + "element vertex 1\n" + layout + std::string(29, '\0')), "no error");

  // The same through `owsim view`: one line, exit 1, no page.
  message(start + "element vertex " + std::to_string(wrapping) + "\n" + layout + ten);
  const test::CliResult view = test::run_cli({"view", run.string()}, dir.path());
  EXPECT_EQ(view.exit_status, 1);
  EXPECT_EQ(view.err, "owsim: " + ply + ": holds 10 bytes after its header, which says " +
                          std::to_string(wrapping) + " vertices of 29 bytes\n");
  EXPECT_FALSE(std::filesystem::exists(run / "report.html"));
}

// The same for points.las: a point count whose product with the record length wraps, and a
// point offset beyond the file.
TEST(ReportPointsLas, CountsThatDoNotFitTheFileAreRefusedInOneLine) {
  const TempDir dir;
  const test::CliResult flown = test::run_cli(
      {"run", (std::filesystem::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml").string(),
       "--out", (dir / "run").string(), "--frames", "2", "--outputs", "las", "--quiet"},
      dir.path());
  ASSERT_EQ(flown.exit_status, 0) << flown.err;
  const std::string las = (dir / "run/points.las").string();
  std::string bytes = test::read_whole_file(las);
  ASSERT_GT(bytes.size(), 375u);
  std::uint16_t record = 0;
  std::memcpy(&record, bytes.data() + 105, 2);
  ASSERT_EQ(record, 30);
  const auto message = [&](const std::string& file) {
    std::ofstream(las, std::ios::binary) << file;
    try {
      (void)read_report_points_las(las, std::nullopt);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // count × 30 ≡ 0 (mod 2^64) for count = 2^63: the old "size < offset + count × 30" passed.
  std::string wrapped = bytes;
  const std::uint64_t count = std::uint64_t{1} << 63;
  std::memcpy(wrapped.data() + 247, &count, 8);
  EXPECT_EQ(message(wrapped),
            las + ": shorter than its header's " + std::to_string(count) + " points");
  std::string far = bytes;
  const std::uint32_t offset = 0xFFFFFFF0u;
  std::memcpy(far.data() + 96, &offset, 4);
  EXPECT_EQ(message(far), las +
                              ": its header size 375 and point offset 4294967280 do not fit its " +
                              std::to_string(bytes.size()) + " bytes");
  EXPECT_EQ(message(bytes), "no error");
}

// points.csv's frame numbers and summary.json's frame count size nothing: a single return at
// frame 1,999,999,999 took 23 GB (a time per frame up to it) before it was killed, and a count of
// 10^15 frames ended in std::bad_alloc.
TEST(FlightReport, FrameNumbersSizeNoTable) {
  const TempDir dir;
  const std::filesystem::path run = dir / "run";
  const test::CliResult flown = test::run_cli(
      {"run", (std::filesystem::path(OWSIM_SOURCE_DIR) / "examples/single_span.yaml").string(),
       "--out", run.string(), "--frames", "2", "--outputs", "summary", "--quiet"},
      dir.path());
  ASSERT_EQ(flown.exit_status, 0) << flown.err;
  std::ofstream(run / "points.csv") << "frame,line,fiber,return,time_s,range_m,e_m,n_m,u_m,class\n"
                                    << "1999999999,0,1,1,0.5,100,1,2,3,wire\n";
  const FlightReport page = write_flight_report(run);
  EXPECT_EQ(page.frames_total, 2'000'000'000);
  EXPECT_EQ(page.frames_shown, 400);
  const nlohmann::json meta =
      nlohmann::json::parse(element(test::read_whole_file(page.file), "owsim-meta"));
  EXPECT_EQ(meta["frames"]["shown"].back(), 1'995'000'000);
  std::string summary = test::read_whole_file(run / "summary.json");
  const std::string two_frames = "\"frames\": 2,";
  const std::size_t at = summary.find(two_frames);
  ASSERT_NE(at, std::string::npos);
  summary.replace(at, two_frames.size(), "\"frames\": 1000000000000000,");
  std::ofstream(run / "summary.json") << summary;
  std::filesystem::remove(page.file);
  try {
    (void)write_flight_report(run);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              (run / "summary.json").string() + ": frames: 1000000000000000 is outside 0..2e9");
  }
  EXPECT_FALSE(std::filesystem::exists(page.file));
}

}  // namespace
}  // namespace owsim
