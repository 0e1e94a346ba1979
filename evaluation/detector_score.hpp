#pragma once
// `owsim score` (INTERFACE.md "Ground truth and detection evidence", docs/evidence.md "Scoring a
// detector"): a detector's output matched to the objects of a run or sweep folder. A detection
// within the gate of an object's surface (evaluation/object_distance.hpp) is a hit on the nearest
// such object, else a false alarm. Per object: whether it came into view, was detected, when and
// from how far first, and the warning time that left before the closest approach; per class:
// detector-level Pd with its Clopper–Pearson interval, and versus range (cumulative, as owsim pd's
// trials); false alarms per flight hour; a confusion table when the detections give classes.
// Written as score.json and score.csv (one row per detection), each complete or not at all.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "evaluation/detection_probability.hpp"

namespace owsim {

struct ScoreOptions {
  std::filesystem::path folder;      // a run folder or a sweep folder
  std::filesystem::path detections;  // a file (run) or a folder of <member>.csv (sweep)
  double gate_m = 5.0;
  double confidence = 0.95;
  RangeBins bins;
  std::optional<std::filesystem::path> out;  // default: `folder`
};

struct ScoredObject {
  std::string flight;  // the member, or the run folder's name
  std::string id;
  std::string object_class;
  bool in_view = false;
  bool detected = false;
  double first_detection_s = 0.0;
  double first_detection_range_m = 0.0;
  std::optional<double> warning_time_s;  // closest approach − first detection
  double farthest_in_view_m = 0.0;
  // The class most of the detections that hit it gave (ties: wire, pole, tree, then by name);
  // "none" when none hit it or none gave a class. The object confusion table's column.
  std::string warned_class = "none";
};

struct ClassScore {
  std::uint64_t objects = 0;   // in view
  std::uint64_t detected = 0;  // of those
  std::vector<double> warning_times_s;  // of those detected with a closest approach, ascending
  ProportionInterval interval;
  std::vector<PdBin> by_range;  // cumulative Pd versus range (the bins' trial counts)
};

struct ScoreReport {
  std::filesystem::path directory;
  std::size_t flights = 0;
  std::uint64_t detections = 0;
  std::uint64_t false_alarms = 0;
  double flight_hours = 0.0;
  std::vector<ScoredObject> objects;
  std::map<std::string, ClassScore> by_class;
  // true class ("none" for a false alarm) → reported class → detections; empty without classes.
  std::map<std::string, std::map<std::string, std::uint64_t>> confusion;
  // Objects in view: true class → warned class (ScoredObject::warned_class, "none" when never
  // warned) → objects. Every class of object in view has a row, with every column the detections
  // or the reference classes (wire, pole, tree, none) name. Empty when the detections give no class.
  std::map<std::string, std::map<std::string, std::uint64_t>> object_confusion;
};

// Scores the detections and writes score.json and score.csv. Throws owsim::Error naming the file,
// line or option for bad input (nothing is written then).
[[nodiscard]] ScoreReport write_score_report(const ScoreOptions& options);

}  // namespace owsim
