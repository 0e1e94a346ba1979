#include "evaluation/false_returns.hpp"

#include <limits>

#include "geometry/error.hpp"

namespace owsim {

FalseReturns& FalseReturns::operator+=(const FalseReturns& other) {
  constexpr std::uint64_t kMost = std::numeric_limits<std::uint64_t>::max();
  if (other.pulses > kMost - pulses || other.false_returns > kMost - false_returns) {
    throw Error("the flights' summaries count more than 2^64 pulses or false returns together");
  }
  pulses += other.pulses;
  false_returns += other.false_returns;
  flight_s += other.flight_s;
  return *this;
}

double FalseReturns::per_s() const {
  if (!(flight_s > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(false_returns) / flight_s;
}

FalseReturns false_returns_of(const FlightFacts& facts) {
  return {facts.pulses, facts.noise_returns, facts.flight_s()};
}

}  // namespace owsim
