#pragma once
// Reading a flight folder back for detection statistics (docs/evidence.md): which flights a folder
// holds (one run, or the members of a sweep in sweep.csv's order), the facts of each flight
// (summary.json, evaluation/flight_facts.hpp), and the truth.csv rows of the objects asked for.
// A run folder is data: every cell of truth.csv is checked against what a run writes, and memory
// grows with the rows kept, never with the values they hold. Every error is one owsim::Error line
// naming the file and line (and the column).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "evaluation/flight_facts.hpp"

namespace owsim {

// The farthest range truth.csv holds and a range bin may reach: beyond the longest range any
// sensor owsim simulates can count (4095 ticks of the slowest clock a scenario may set, 614 km).
inline constexpr double kMaxRangeM = 1'000'000.0;

struct CampaignFlight {
  std::string name;  // the sweep member ("0042"), or the run folder's name
  std::filesystem::path directory;
};

// The flights under `directory`: the members listed in its sweep.csv (member m in the folder
// `owsim sweep` names, zero-padded to the widest member number; each member once, in increasing
// order, as the sweep writes them), or the folder itself when it holds a summary.json. Throws
// owsim::Error when it is neither.
[[nodiscard]] std::vector<CampaignFlight> campaign_flights(const std::filesystem::path& directory);

// One truth.csv row, of the columns detection statistics use.
struct TruthEntry {
  std::int64_t frame = 0;
  double time_s = 0.0;
  double range_m = 0.0;
  bool in_view = false;
  std::uint64_t returns = 0;
  double closing_speed_mps = 0.0;
};

// The rows of one object, in file (frame) order: frames strictly increase.
struct ObjectTrack {
  std::string id;
  std::string object_class;
  std::vector<TruthEntry> rows;
};

using WantedObject = std::function<bool(std::string_view id, std::string_view object_class)>;

// The rows of truth.csv whose object `wanted(id, class)` accepts, one track per object in the
// order each first appears; `facts` are the flight's (frames lie in [0, facts.frames)). Every
// row's cells are checked, wanted or not. Throws owsim::Error naming the file (and line and
// column) when it is missing, has another header, or a row no run writes.
[[nodiscard]] std::vector<ObjectTrack> read_truth_csv(const std::filesystem::path& truth_csv,
                                                      const FlightFacts& facts,
                                                      const WantedObject& wanted);

// The same from the file's text; `name` stands for the file in messages.
[[nodiscard]] std::vector<ObjectTrack> parse_truth_csv(std::string_view text,
                                                       const std::string& name,
                                                       const FlightFacts& facts,
                                                       const WantedObject& wanted);

}  // namespace owsim
