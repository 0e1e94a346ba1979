#include "evaluation/detector_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "evaluation/detection_match.hpp"
#include "evaluation/detections_csv.hpp"
#include "evaluation/object_distance.hpp"
#include "evaluation/truth_table.hpp"
#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/json_text.hpp"
#include "io/trajectory/trajectory_loader.hpp"
#include "owsim/version.hpp"

namespace owsim {
namespace {

constexpr std::string_view kScoreCsvHeader =
    "flight,line,time_s,e_m,n_m,u_m,class,track,object,object_class,distance_m";

// One flight scored: its objects, false alarms, and score.csv rows appended to `rows`.
struct FlightScore {
  std::vector<ScoredObject> objects;
  std::uint64_t detections = 0;
  std::uint64_t false_alarms = 0;
  double hours = 0.0;
};

// The class most detections of an object gave: ties to wire, pole, tree, then the first by name.
std::string warned_class(const std::map<std::string, std::uint64_t>& classes) {
  const auto rank = [](const std::string& name) {
    return name == "wire" ? 0 : name == "pole" ? 1 : name == "tree" ? 2 : 3;
  };
  const std::pair<const std::string, std::uint64_t>* best = nullptr;
  for (const auto& entry : classes) {
    if (best == nullptr || entry.second > best->second ||
        (entry.second == best->second && rank(entry.first) < rank(best->first))) {
      best = &entry;
    }
  }
  return best == nullptr ? "none" : best->first;
}

nlohmann::json warning_time_json(const std::vector<double>& times) {
  if (times.empty()) {
    return {{"objects", 0}, {"min_s", nullptr}, {"median_s", nullptr}, {"mean_s", nullptr}};
  }
  double sum = 0.0;
  for (const double t : times) sum += t;
  const std::size_t n = times.size();
  const double median = n % 2 == 1 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  return {{"objects", n},
          {"min_s", times.front()},
          {"median_s", median},
          {"mean_s", sum / static_cast<double>(n)}};
}

FlightScore score_flight(const CampaignFlight& flight, const std::filesystem::path& detections,
                         const ScoreOptions& options, ScoreReport& report, std::string& rows) {
  const FlownScene flown_scene = load_flown_scene(flight);
  const Scenario& scenario = flown_scene.scenario;
  const LocalFrame& frame = flown_scene.frame;
  const Scene& scene = flown_scene.scene;
  const Trajectory trajectory = load_trajectory(scenario, frame);
  DetectionMatcher matcher(scene, options.gate_m);
  const FlightFacts facts = read_flight_facts(flight.directory / "summary.json");
  const std::vector<ObjectTrack> tracks =
      read_truth_csv(flight.directory / "truth.csv", facts,
                     [](std::string_view, std::string_view) { return true; });

  FlightScore score;
  score.hours = facts.flight_s() / 3600.0;
  // The objects by index, in scene order.
  const std::size_t count = named_object_count(scene);
  std::unordered_map<std::string, std::uint32_t> index_of;
  for (std::uint32_t object = 0; object < count; ++object) {
    index_of.emplace(named_object_id(scene, object), object);
  }
  std::vector<std::optional<double>> first_hit_s(count);
  std::vector<std::map<std::string, std::uint64_t>> hit_classes(count);
  const DetectionFlight flown{frame, scenario.scan.start_s,
                              scenario.scan.start_s + facts.flight_s()};
  read_detections_csv(detections, flown, [&](const Detection& detection) {
    ++score.detections;
    const std::optional<ObjectHit> hit = matcher.hit(detection.enu_m);
    const std::string true_class =
        hit ? std::string(to_string(named_object_class(scene, hit->object))) : std::string("none");
    if (hit) {
      std::optional<double>& first = first_hit_s[hit->object];
      if (!first || detection.time_s < *first) first = detection.time_s;
      if (!detection.object_class.empty()) ++hit_classes[hit->object][detection.object_class];
    } else {
      ++score.false_alarms;
    }
    if (!detection.object_class.empty()) ++report.confusion[true_class][detection.object_class];
    rows += csv_cell(flight.name);
    rows += ',';
    append_csv_integer(rows, detection.line);
    rows += ',';
    append_csv_fixed(rows, detection.time_s, 6);
    for (int axis = 0; axis < 3; ++axis) {
      rows += ',';
      append_csv_fixed(rows, detection.enu_m[axis], 3);
    }
    rows += ',' + csv_cell(detection.object_class) + ',' + csv_cell(detection.track) + ',';
    if (hit) {
      rows += csv_cell(named_object_id(scene, hit->object)) + ',' + true_class + ',';
      append_csv_fixed(rows, hit->distance_m, 3);
    } else {
      rows += ",,";
    }
    rows += '\n';
  });

  // Every object the truth names (within range at some frame), and any other one detected.
  std::vector<bool> listed(count, false);
  const auto scored = [&](std::uint32_t object, const ObjectTrack* track) {
    ScoredObject out;
    out.flight = flight.name;
    out.id = named_object_id(scene, object);
    out.object_class = to_string(named_object_class(scene, object));
    std::optional<double> closest_s;
    double closest_m = std::numeric_limits<double>::infinity();
    if (track != nullptr) {
      for (const TruthEntry& row : track->rows) {
        if (row.in_view) {
          out.in_view = true;
          out.farthest_in_view_m = std::max(out.farthest_in_view_m, row.range_m);
        }
        if (row.range_m < closest_m) {
          closest_m = row.range_m;
          closest_s = row.time_s;
        }
      }
    }
    if (const std::optional<double>& first = first_hit_s[object]) {
      out.detected = true;
      out.first_detection_s = *first;
      const SensorPlacement placement =
          sensor_placement(trajectory.pose_at(*first), scenario.mount, scenario.scan.model);
      out.first_detection_range_m = distance_to_object_m(scene, object, placement.origin_enu_m);
      if (closest_s) out.warning_time_s = *closest_s - *first;
      out.warned_class = warned_class(hit_classes[object]);
    }
    return out;
  };
  for (const ObjectTrack& track : tracks) {
    const auto found_index = index_of.find(track.id);
    if (found_index == index_of.end()) {
      throw input_error((flight.directory / "truth.csv").string(),
                        "object '" + track.id + "' is not in " +
                            (flight.directory / "scenario.yaml").string());
    }
    listed[found_index->second] = true;
    score.objects.push_back(scored(found_index->second, &track));
  }
  for (std::uint32_t object = 0; object < count; ++object) {
    if (!listed[object] && first_hit_s[object]) score.objects.push_back(scored(object, nullptr));
  }
  return score;
}

nlohmann::json interval_json(std::uint64_t hits, std::uint64_t count,
                             const ProportionInterval& interval) {
  const auto number = [](double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  };
  return {{"pd", count > 0 ? nlohmann::json(static_cast<double>(hits) / static_cast<double>(count))
                           : nlohmann::json(nullptr)},
          {"pd_lo", number(interval.lower)},
          {"pd_hi", number(interval.upper)}};
}

nlohmann::json score_json(const ScoreReport& report, const ScoreOptions& options) {
  nlohmann::json objects = nlohmann::json::array();
  for (const ScoredObject& object : report.objects) {
    nlohmann::json entry = {{"flight", object.flight},
                            {"id", object.id},
                            {"class", object.object_class},
                            {"in_view", object.in_view},
                            {"detected", object.detected},
                            {"warned_class", object.warned_class},
                            {"first_detection_s", nullptr},
                            {"first_detection_range_m", nullptr},
                            {"warning_time_s", nullptr}};
    if (object.detected) {
      entry["first_detection_s"] = object.first_detection_s;
      entry["first_detection_range_m"] = object.first_detection_range_m;
      if (object.warning_time_s) entry["warning_time_s"] = *object.warning_time_s;
    }
    objects.push_back(std::move(entry));
  }
  nlohmann::json by_class = nlohmann::json::object();
  for (const auto& [name, score] : report.by_class) {
    nlohmann::json entry = {{"objects", score.objects}, {"detected", score.detected}};
    entry.update(interval_json(score.detected, score.objects, score.interval));
    nlohmann::json by_range = nlohmann::json::array();
    for (const PdBin& bin : score.by_range) {
      nlohmann::json row = {{"range_lo_m", bin.range_lo_m},
                            {"range_hi_m", bin.range_hi_m},
                            {"objects", bin.trials},
                            {"detected", bin.trials_detected}};
      row.update(interval_json(bin.trials_detected, bin.trials, bin.cumulative_interval));
      by_range.push_back(std::move(row));
    }
    entry["pd_by_range"] = std::move(by_range);
    entry["warning_time"] = warning_time_json(score.warning_times_s);
    by_class[name] = std::move(entry);
  }
  return {{"flights", report.flights},
          {"gate_m", options.gate_m},
          {"confidence", options.confidence},
          {"interval", kIntervalMethod},
          {"detections", report.detections},
          {"false_alarms", report.false_alarms},
          {"flight_hours", report.flight_hours},
          {"false_alarms_per_hour",
           report.flight_hours > 0.0
               ? nlohmann::json(static_cast<double>(report.false_alarms) / report.flight_hours)
               : nlohmann::json(nullptr)},
          {"by_class", by_class},
          {"confusion", report.confusion},
          {"object_confusion", report.object_confusion},
          {"objects", objects},
          {"definitions", "docs/evidence.md (owsim " + std::string(version_string) + ")"}};
}

void write_file(const std::filesystem::path& path, std::string_view text) {
  AtomicOutputFile file(path);
  file.write(text);
  file.commit();
}

}  // namespace

ScoreReport write_score_report(const ScoreOptions& options) {
  validate_gate_m(options.gate_m);
  validate(DetectionCriterion{}, options.bins, options.confidence);
  ScoreReport report;
  report.directory = options.out ? *options.out : options.folder;
  const std::vector<CampaignFlight> flights = campaign_flights(options.folder);
  report.flights = flights.size();
  const std::vector<std::filesystem::path> files =
      detections_files(options.folder, flights, options.detections);
  std::error_code error;
  std::string rows(kScoreCsvHeader);
  rows += '\n';
  std::map<std::string, std::vector<Trial>> trials;
  for (std::size_t f = 0; f < flights.size(); ++f) {
    const CampaignFlight& flight = flights[f];
    const std::filesystem::path& file = files[f];
    FlightScore score = score_flight(flight, file, options, report, rows);
    report.detections += score.detections;
    report.false_alarms += score.false_alarms;
    report.flight_hours += score.hours;
    for (ScoredObject& object : score.objects) {
      if (object.in_view) {
        ClassScore& of_class = report.by_class[object.object_class];
        ++of_class.objects;
        if (object.detected) ++of_class.detected;
        if (object.warning_time_s) of_class.warning_times_s.push_back(*object.warning_time_s);
        ++report.object_confusion[object.object_class][object.warned_class];
        // A detection in the frame the object came into view lies at the frame's start, a few
        // metres farther than the truth's range at the frame's middle: no farther than it was seen.
        trials[object.object_class].push_back(
            {object.farthest_in_view_m,
             object.detected ? std::optional(std::min(object.first_detection_range_m,
                                                      object.farthest_in_view_m))
                             : std::nullopt});
      }
      report.objects.push_back(std::move(object));
    }
  }
  // Detections without classes warn of nothing in particular: no object table.
  if (report.confusion.empty()) report.object_confusion.clear();
  // Every row of the object table has every column: the reference classes and any other named.
  std::vector<std::string> columns = {"wire", "pole", "tree", "none"};
  for (const auto& [truth, row] : report.object_confusion) {
    for (const auto& [warned, objects] : row) {
      if (std::find(columns.begin(), columns.end(), warned) == columns.end()) {
        columns.push_back(warned);
      }
    }
  }
  for (auto& [truth, row] : report.object_confusion) {
    for (const std::string& column : columns) row.try_emplace(column, 0);
  }
  for (auto& [name, score] : report.by_class) {
    std::sort(score.warning_times_s.begin(), score.warning_times_s.end());
    score.interval = clopper_pearson(score.detected, score.objects, options.confidence);
    score.by_range = empty_bins(options.bins);
    add_trials(trials[name], score.by_range);
    set_intervals(score.by_range, options.confidence);
  }
  std::filesystem::create_directories(report.directory, error);
  if (error) {
    throw file_error(report.directory.string(),
                     "cannot create the output folder: " + error.message());
  }
  const std::string json = json_text(score_json(report, options), 2) + "\n";
  write_file(report.directory / "score.csv", rows);
  write_file(report.directory / "score.json", json);
  return report;
}

}  // namespace owsim
