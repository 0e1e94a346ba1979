#include "owsim/flight_report.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "io/report/flight_folder.hpp"
#include "io/report/report_cloud.hpp"
#include "io/report/report_evidence.hpp"
#include "io/report/report_frames.hpp"
#include "io/report/report_page.hpp"
#include "io/report/report_points.hpp"
#include "io/report/report_scene.hpp"
#include "io/report/report_summary.hpp"
#include "io/report/report_trajectory.hpp"
#include "io/scenario/scenario_loader.hpp"
#include "io/scenario/scene_builder.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "owsim/report_warnings.hpp"
#include "owsim/version.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/scan_pattern.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxCylinders = 20'000;
// Warning tracks the page draws (a long flight over woods warns of thousands of trees).
constexpr std::size_t kMaxWarningTracks = 20'000;
constexpr std::size_t kMaxTrajectoryRows = 20'000;
constexpr std::size_t kMaxScenarioFrames = 1'000'000;  // ~4 days of frames: a bound, not a limit

std::string thousands(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

json trajectory_json(const ReportTrajectory& trajectory) {
  json columns = {{"time_s", json::array()},
                  {"e_m", json::array()},
                  {"n_m", json::array()},
                  {"u_m", json::array()}};
  const std::size_t n = trajectory.rows.size();
  const std::size_t keep = std::min(n, kMaxTrajectoryRows);
  for (std::size_t i = 0; i < keep; ++i) {
    const auto& row = trajectory.rows[keep == 1 ? 0 : i * (n - 1) / (keep - 1)];
    columns["time_s"].push_back(row.time_s);
    columns["e_m"].push_back(std::round(row.e_m * 100) / 100);
    columns["n_m"].push_back(std::round(row.n_m * 100) / 100);
    columns["u_m"].push_back(std::round(row.u_m * 100) / 100);
  }
  return columns;
}

json frames_json(const ReportFrames& frames, const RangeImageLayout& layout,
                 const std::optional<ReportTrajectory>& trajectory, const ReportPoints& points) {
  json time_s = json::array(), pose = json::array();
  for (const std::int64_t frame : frames.frames) {
    const auto f = static_cast<std::size_t>(frame);
    if (trajectory && f < trajectory->rows.size()) {
      const auto& row = trajectory->rows[f];
      time_s.push_back(row.time_s);
      pose.push_back({row.e_m, row.n_m, row.u_m, row.roll_deg, row.pitch_deg, row.heading_deg});
      continue;
    }
    const auto first = points.frame_first_time_s.find(static_cast<std::int32_t>(frame));
    time_s.push_back(first != points.frame_first_time_s.end() ? json(first->second)
                                                              : json(nullptr));
    pose.push_back(nullptr);
  }
  json alpha = json::array();
  for (const double a : layout.alpha_deg) alpha.push_back(std::round(a * 1e4) / 1e4);
  return {{"total", frames.frames_total},
          {"shown", frames.frames},
          {"time_s", std::move(time_s)},
          {"pose", std::move(pose)},
          {"rows", layout.fibers.size()},
          {"lines", layout.lines},
          {"row_fiber", layout.fibers},
          {"row_alpha_deg", std::move(alpha)},
          {"beta_first_deg", layout.beta_first_deg},
          {"beta_last_deg", layout.beta_last_deg}};
}

// trajectory.csv as a run of the scenario writes it: the pose at every frame start within the
// trajectory.
ReportTrajectory scenario_trajectory(const Scenario& scenario) {
  const LocalFrame frame(scenario.origin);
  const Trajectory flown = load_trajectory(scenario, frame);
  ReportTrajectory out;
  for (std::int64_t k = 0;; ++k) {
    const double t = pulse_time_s(scenario.scan, k, 0);
    if (t > flown.end_s() || out.rows.size() >= kMaxScenarioFrames) break;
    const Pose pose = flown.pose_at(t);
    const Geodetic g = frame.geodetic_from_enu(pose.position_enu_m);
    const Eigen::Vector3d& p = pose.position_enu_m;
    out.rows.push_back({t, g.lat_deg, g.lon_deg, g.h_m, p.x(), p.y(), p.z(), pose.attitude.roll_deg,
                        pose.attitude.pitch_deg, pose.attitude.heading_deg});
  }
  return out;
}

// A class slot of ReportCloud: the class's name, "unknown" for the last.
std::string class_slot_name(std::size_t slot) {
  return slot < kSurfaceClassCount ? std::string(to_string(static_cast<SurfaceClass>(slot)))
                                   : std::string("unknown");
}

json cloud_json(const ReportCloud& cloud, const std::string& source) {
  json by_class = json::object();
  for (std::size_t slot = 0; slot < kCloudClassSlots; ++slot) {
    if (cloud.total_by_class[slot] == 0) continue;
    by_class[class_slot_name(slot)] = {{"total", cloud.total_by_class[slot]},
                                       {"shown", cloud.shown_by_class[slot]}};
  }
  return {{"source", source},         {"total", cloud.total},     {"shown", cloud.shown()},
          {"box_min", cloud.box_min}, {"box_max", cloud.box_max}, {"by_class", by_class}};
}

std::vector<std::uint8_t> cloud_bytes(const ReportCloud& cloud) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(cloud.shown() * 9);
  const auto put16 = [&](std::uint16_t v) {
    bytes.push_back(static_cast<std::uint8_t>(v & 0xFF));
    bytes.push_back(static_cast<std::uint8_t>(v >> 8));
  };
  for (const std::uint16_t v : cloud.xyz) put16(v);
  for (const std::uint16_t v : cloud.range_dm) put16(v);
  bytes.insert(bytes.end(), cloud.surface.begin(), cloud.surface.end());
  return bytes;
}

std::string thinning_note(const ReportCloud& cloud) {
  std::string note = "The 3D view shows " + thousands(cloud.shown()) + " of " +
                     thousands(cloud.total) + " returns:";
  for (std::size_t slot = 0; slot < kCloudClassSlots; ++slot) {
    const std::uint64_t total = cloud.total_by_class[slot], shown = cloud.shown_by_class[slot];
    if (total == 0) continue;
    note += ' ';
    note += class_slot_name(slot);
    note += shown == total
                ? " all;"
                : " 1 in " +
                      std::to_string((total + shown - 1) / std::max<std::uint64_t>(shown, 1)) + ";";
  }
  note.back() = '.';
  return note;
}

// The page's parts, read and laid out one after the other: each step adds its part of the meta
// JSON and a note for whatever the folder lacks.
class PageAssembly {
 public:
  PageAssembly(const FlightFolder& folder, const FlightReportOptions& options)
      : folder_(folder), options_(options) {
    report_.file = options.out.empty() ? folder.directory / "report.html" : options.out;
    meta_["generator"] = std::string("owsim ") + version_string;
    meta_["folder"] = std::filesystem::absolute(folder.directory).lexically_normal().string();
    title_ = folder.directory.filename().string();
    if (folder.hellas_words) scan_.model = SensorModel::hellas;
  }

  void add_summary() {
    meta_["summary"] = nullptr;
    meta_["objects"] = json::array();
    meta_["objects_total"] = 0;
    if (!folder_.summary_json) {
      note(
          "No summary.json in this folder (a decoded recording?): no run summary and no ground "
          "truth.");
      return;
    }
    ReportSummary read = read_report_summary(*folder_.summary_json, options_.max_objects);
    if (read.objects_total > options_.max_objects) {
      note("The ground-truth table lists the first " + thousands(options_.max_objects) + " of " +
           thousands(read.objects_total) + " objects by first-seen time.");
    }
    const auto scenario = read.facts.find("scenario");
    if (scenario != read.facts.end() && scenario->is_string())
      title_ = scenario->get<std::string>();
    const auto frames = read.facts.find("frames");
    if (frames != read.facts.end() && frames->is_number_integer()) {
      frames_hint_ = frames->get<std::int64_t>();
      if (frames_hint_ < 0 || frames_hint_ > kMaxReportFrames) {
        throw input_error(folder_.summary_json->string() + ": frames",
                          frames->dump() + " is outside 0..2e9");
      }
    }
    meta_["summary"] = std::move(read.facts);
    meta_["objects"] = std::move(read.objects);
    meta_["objects_total"] = read.objects_total;
  }

  // owsim pd's, owsim roc's and owsim score's files, when they were written into the folder.
  void add_evidence() {
    const json evidence = report_evidence_json(folder_.directory, options_.max_objects);
    meta_["pd"] = evidence["pd"];
    meta_["roc"] = evidence["roc"];
    meta_["score"] = evidence["score"];
  }

  // The reference detector's (or any detector's) warnings, when the folder holds detections.csv
  // and the scenario is known (its origin places WGS-84 rows; its frame period dates them).
  void add_warnings() {
    meta_["warnings"] = nullptr;
    const std::filesystem::path csv = folder_.directory / "detections.csv";
    std::error_code error;
    if (!std::filesystem::is_regular_file(csv, error)) return;
    if (!scenario_ || frames_hint_ < 1) {
      note(
          "detections.csv is not drawn: its warnings need the flight's scenario (--scenario) and "
          "summary.json's frame count.");
      return;
    }
    meta_["warnings"] = report_warnings_json(csv, *scenario_, frames_hint_, kMaxWarningTracks);
    const std::size_t total = meta_["warnings"]["tracks_total"].get<std::size_t>();
    if (total > kMaxWarningTracks) {
      note("Warnings: the first " + thousands(kMaxWarningTracks) + " of " + thousands(total) +
           " tracks drawn.");
    }
  }

  void add_scene() {
    meta_["scene"] = nullptr;
    if (!options_.scenario) {
      note(
          "Scene objects (wires, poles, trees, meshes) are drawn when owsim view is given the "
          "flight's scenario: --scenario FILE.");
    } else {
      const Scenario& scenario = scenario_.emplace(load_scenario(*options_.scenario));
      scan_ = scenario.scan;
      const Scene scene = build_scene(scenario);
      meta_["scene"] = report_scene_json(scene, kMaxCylinders);
      meta_["scenario_file"] = options_.scenario->string();
      if (scene.cylinders.size() > kMaxCylinders) {
        note("Poles and trees: " + thousands(kMaxCylinders) + " of " +
             thousands(scene.cylinders.size()) + " drawn, evenly chosen.");
      }
    }
    meta_["sensor"] = {{"model", scan_.model == SensorModel::hellas ? "HELLAS" : "MilOWS"},
                       {"timeout_range_m", timeout_range_m(scan_.counter)}};
  }

  void add_trajectory() {
    meta_["trajectory"] = nullptr;
    if (folder_.trajectory_csv) {
      trajectory_ = read_report_trajectory(*folder_.trajectory_csv);
    } else if (scenario_) {
      trajectory_ = scenario_trajectory(*scenario_);
      note(
          "No trajectory.csv in this folder (a decoded recording?): the flight path and poses "
          "are the scenario's trajectory at each frame start (a decode's --trajectory file is "
          "not known here).");
    } else {
      note(
          "No trajectory.csv in this folder: no flight path and no poses (--scenario gives the "
          "scenario's).");
    }
    if (trajectory_) meta_["trajectory"] = trajectory_json(*trajectory_);
  }

  void read_points() {
    if (folder_.points_csv) {
      points_ = read_report_points_csv(*folder_.points_csv);
    } else if (folder_.points_ply) {
      points_ = read_report_points_ply(*folder_.points_ply);
    } else if (folder_.points_las) {
      points_ = read_report_points_las(*folder_.points_las, las_origin());
    } else {
      note(
          "No point file in this folder (the run wrote words only?): no returns to show. owsim "
          "decode, or a run with --outputs points, writes them.");
      return;
    }
    if (points_.size() == 0) note("The flight has no returns: the sensor saw nothing.");
  }

  void add_frames() {
    meta_["frames"] = nullptr;
    if (!points_.pulses_known) {
      if (points_.size() > 0) {
        note(
            "The frame player needs points.csv (frame, line and fiber of each return); this "
            "folder has " +
            points_.source + " only.");
      }
      return;
    }
    const RangeImageLayout layout = range_image_layout(scan_);
    const ReportFrames frames = report_frames(points_, layout, frames_hint_, options_.max_frames);
    report_.frames_total = frames.frames_total;
    report_.frames_shown = static_cast<std::int64_t>(frames.frames.size());
    if (report_.frames_shown < report_.frames_total) {
      note("The frame player holds " + thousands(report_.frames_shown) + " of " +
           thousands(report_.frames_total) + " frames, evenly spread (--max-frames).");
    }
    if (frames.returns_outside > 0) {
      note(thousands(frames.returns_outside) +
           " returns name a line or fiber outside the sensor's frame and are left out of the "
           "range images.");
    }
    meta_["frames"] = frames_json(frames, layout, trajectory_, points_);
    frames_blob_ = deflate_base64(frames.planes);
  }

  void add_cloud() {
    const ReportCloud cloud = report_cloud(points_, options_.max_points);
    report_.points_total = cloud.total;
    report_.points_shown = cloud.shown();
    if (cloud.shown() < cloud.total) note(thinning_note(cloud));
    meta_["cloud"] = cloud_json(cloud, points_.source);
    cloud_blob_ = deflate_base64(cloud_bytes(cloud));
  }

  FlightReport write() {
    meta_["title"] = title_;
    meta_["notes"] = report_.notes;
    report_.bytes = write_report_page(report_.file, "owsim — " + title_, meta_.dump(), frames_blob_,
                                      cloud_blob_);
    return std::move(report_);
  }

 private:
  void note(std::string text) { report_.notes.push_back(std::move(text)); }

  // LAS holds UTM: the scenario's origin, or the one trajectory.csv implies, brings it home.
  std::optional<Geodetic> las_origin() {
    if (scenario_) return scenario_->origin;
    if (trajectory_ && !trajectory_->rows.empty()) {
      const TrajectoryRow& row = trajectory_->rows.front();
      return origin_of_frame({row.lat_deg, row.lon_deg, row.h_m}, {row.e_m, row.n_m, row.u_m});
    }
    note(
        "points.las is shown in its own grid (easting, northing and height less the file's "
        "offsets): without trajectory.csv or --scenario there is no scenario origin to place "
        "it.");
    return std::nullopt;
  }

  const FlightFolder& folder_;
  const FlightReportOptions& options_;
  FlightReport report_;
  json meta_ = json::object();
  std::string title_;
  ScanParams scan_;
  std::optional<Scenario> scenario_;
  std::optional<ReportTrajectory> trajectory_;
  std::int64_t frames_hint_ = 0;  // summary.json's frame count
  ReportPoints points_;
  std::string frames_blob_, cloud_blob_;
};

}  // namespace

FlightReport write_flight_report(const std::filesystem::path& folder,
                                 const FlightReportOptions& options) {
  if (options.max_frames < 1) throw input_error("--max-frames", "must be at least 1");
  if (options.max_points < 1) throw input_error("--max-points", "must be at least 1");
  const FlightFolder found = find_flight_folder(folder);
  // A run folder describes itself: its scenario.yaml stands in for --scenario.
  FlightReportOptions with_scenario = options;
  if (!with_scenario.scenario && std::filesystem::is_regular_file(folder / "scenario.yaml")) {
    with_scenario.scenario = folder / "scenario.yaml";
  }
  PageAssembly page(found, with_scenario);
  page.add_summary();
  page.add_evidence();
  page.add_scene();
  page.add_warnings();
  page.add_trajectory();
  page.read_points();
  page.add_frames();
  page.add_cloud();
  return page.write();
}

}  // namespace owsim
