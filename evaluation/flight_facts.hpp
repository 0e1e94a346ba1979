#pragma once
// A run's facts from its summary.json, as `owsim pd`, `roc` and `score` read them back
// (docs/evidence.md): the frames it flew, the frame period, the pulses it fired and the receiver's
// false returns (returns.noise). summary.json is data: each value is checked against what a run
// can write, and only these keys are kept while the file is parsed (the objects of a large scene
// are parsed past, not stored). Every error is one owsim::Error line naming the file and the key.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace owsim {

// What a run can write. A frame is 2 to 2^20 pulses (sensor/scan_params_check.cpp) fired at 1 Hz
// to 1 MHz (io/scenario/value_ranges.hpp): periods of 2 µs to 12 days, here with room on both
// sides; more frames than a day's flight at the fastest frame rate (4.3·10¹⁰) and few enough that
// frame arithmetic cannot overflow.
inline constexpr double kMinFramePeriodS = 1e-6;
inline constexpr double kMaxFramePeriodS = 1e7;
inline constexpr std::int64_t kMaxFrames = 1'000'000'000'000;
inline constexpr std::uint64_t kMaxPulsesPerFrame = std::uint64_t{1} << 20;
// A pulse has a first and a second return at most (SENSOR-SPEC §8, its data word).
inline constexpr std::uint64_t kMaxReturnsPerPulse = 2;

struct FlightFacts {
  std::int64_t frames = 0;
  double frame_period_s = 0.0;
  std::uint64_t pulses = 0;
  std::uint64_t noise_returns = 0;  // returns.noise; 0 in summaries from before it was counted
  [[nodiscard]] double flight_s() const { return static_cast<double>(frames) * frame_period_s; }
};

// The facts of a run's summary.json. Throws owsim::Error naming the file (and the key) when it is
// missing, is not an owsim summary or holds a value no run writes.
[[nodiscard]] FlightFacts read_flight_facts(const std::filesystem::path& summary_json);

// The same from the file's text; `name` stands for the file in messages.
[[nodiscard]] FlightFacts parse_flight_facts(std::string_view text, const std::string& name);

}  // namespace owsim
