#pragma once
// Reading a flight folder back for detection statistics (docs/evidence.md): which flights a folder
// holds (one run, or the members of a sweep in sweep.csv's order), the facts of each flight
// (frames, frame period, from summary.json), and the truth.csv rows of the objects asked for.
// Every error is one owsim::Error line naming the file and line.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace owsim {

struct CampaignFlight {
  std::string name;  // the sweep member ("0042"), or the run folder's name
  std::filesystem::path directory;
};

// The flights under `directory`: the members listed in its sweep.csv (member m in the folder
// `owsim sweep` names, zero-padded to the widest member number), or the folder itself when it
// holds a summary.json. Throws owsim::Error when it is neither.
[[nodiscard]] std::vector<CampaignFlight> campaign_flights(const std::filesystem::path& directory);

struct FlightFacts {
  std::int64_t frames = 0;
  double frame_period_s = 0.0;
  double flight_s() const { return static_cast<double>(frames) * frame_period_s; }
};

// frames and frame_period_s of a run's summary.json.
[[nodiscard]] FlightFacts read_flight_facts(const std::filesystem::path& summary_json);

// One truth.csv row, of the columns detection statistics use.
struct TruthEntry {
  std::int64_t frame = 0;
  double time_s = 0.0;
  double range_m = 0.0;
  bool in_view = false;
  std::uint64_t returns = 0;
  double closing_speed_mps = 0.0;
};

// The rows of one object, in file (frame) order.
struct ObjectTrack {
  std::string id;
  std::string object_class;
  std::vector<TruthEntry> rows;
};

// The rows of truth.csv whose object `wanted(id, class)` accepts, one track per object in the
// order each first appears. Throws owsim::Error naming the file (and line) when it is missing, has
// another header or a malformed row.
[[nodiscard]] std::vector<ObjectTrack> read_truth_csv(
    const std::filesystem::path& truth_csv,
    const std::function<bool(std::string_view id, std::string_view object_class)>& wanted);

}  // namespace owsim
