#include "evaluation/false_returns.hpp"

#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "evaluation/truth_table.hpp"
#include "geometry/error.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxSummaryBytes = std::uintmax_t{1} << 30;

}  // namespace

FalseReturns& FalseReturns::operator+=(const FalseReturns& other) {
  pulses += other.pulses;
  false_returns += other.false_returns;
  flight_s += other.flight_s;
  return *this;
}

double FalseReturns::per_s() const {
  if (!(flight_s > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(false_returns) / flight_s;
}

FalseReturns read_false_returns(const std::filesystem::path& summary_json) {
  FalseReturns counts;
  counts.flight_s = read_flight_facts(summary_json).flight_s();
  try {
    const nlohmann::json summary =
        nlohmann::json::parse(read_input_file(summary_json, "run summary", kMaxSummaryBytes));
    counts.pulses = summary.at("pulses").get<std::uint64_t>();
    const nlohmann::json& returns = summary.at("returns");
    if (returns.contains("noise")) counts.false_returns = returns.at("noise").get<std::uint64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw input_error(summary_json.string(), std::string("not an owsim summary: ") + e.what());
  }
  return counts;
}

}  // namespace owsim
