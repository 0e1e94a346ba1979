#pragma once
// The sensor's false returns of a flight, from its summary.json (INTERFACE.md "Receiver noise and
// sunlight"): what `owsim pd` (pd.json `false_returns`, `pulses`, `false_returns_per_s`) and
// `owsim roc` (roc.csv) report — the receiver's false triggers, before any detector. Flights pool
// by summing counts and seconds; the rate per second is over flight time, frames × frame period
// (as `owsim score`'s false alarms per flight hour).
#include <cstdint>

#include "evaluation/flight_facts.hpp"

namespace owsim {

struct FalseReturns {
  std::uint64_t pulses = 0;
  std::uint64_t false_returns = 0;  // summary.json returns.noise
  double flight_s = 0.0;            // frames × frame_period_s
  // Throws owsim::Error when a count would pass 2^64 (summaries no set of runs writes).
  FalseReturns& operator+=(const FalseReturns& other);
  // false_returns ÷ flight_s; NaN for no flight time.
  [[nodiscard]] double per_s() const;
};

// pulses, returns.noise (0 when absent: summaries written before the receiver had noise) and the
// flight seconds of a run's summary.json facts (evaluation/flight_facts.hpp).
[[nodiscard]] FalseReturns false_returns_of(const FlightFacts& facts);

}  // namespace owsim
