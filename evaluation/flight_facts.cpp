#include "evaluation/flight_facts.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

constexpr std::uintmax_t kMaxSummaryBytes = std::uintmax_t{1} << 30;
constexpr std::size_t kShownChars = 40;

using Json = nlohmann::json;

// The value as a message shows it: JSON text (one line), cut after kShownChars.
std::string shown(const Json& value) {
  std::string text = value.dump();
  if (text.size() > kShownChars) text = text.substr(0, kShownChars) + "…";
  return text;
}

// A whole number in [lo, hi] as a run writes it (no sign, no fraction, no exponent).
std::uint64_t whole_number(const Json& value, const std::string& name, std::string_view key,
                           std::uint64_t lo, std::uint64_t hi) {
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() < lo ||
      value.get<std::uint64_t>() > hi) {
    throw input_error(name, std::string(key) + ": must be a whole number in [" +
                                std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                                shown(value));
  }
  return value.get<std::uint64_t>();
}

const Json& required(const Json& summary, const std::string& name, const char* key) {
  const auto found = summary.find(key);
  if (found == summary.end()) {
    throw input_error(name, std::string("not an owsim summary: no ") + key);
  }
  return *found;
}

}  // namespace

FlightFacts parse_flight_facts(std::string_view text, const std::string& name) {
  Json summary;
  try {
    // Only the keys read here are kept: what else the summary holds is parsed and dropped.
    summary = Json::parse(
        text.begin(), text.end(), [](int depth, Json::parse_event_t event, Json& parsed) {
          if (depth != 1 || event != Json::parse_event_t::key) return true;
          const auto& key = parsed.get_ref<const std::string&>();
          return key == "frames" || key == "frame_period_s" || key == "pulses" || key == "returns";
        });
  } catch (const Json::exception& e) {
    throw input_error(name, std::string("not an owsim summary: ") + e.what());
  }
  if (!summary.is_object()) throw input_error(name, "not an owsim summary: not a JSON object");
  FlightFacts facts;
  facts.frames =
      static_cast<std::int64_t>(whole_number(required(summary, name, "frames"), name, "frames", 1,
                                             static_cast<std::uint64_t>(kMaxFrames)));
  if (!summary.contains("frame_period_s")) {
    throw input_error(name,
                      "no frame_period_s (written by an owsim before 0.2: run the flight again)");
  }
  const Json& period = summary.at("frame_period_s");
  if (!period.is_number() ||
      !(period.get<double>() >= kMinFramePeriodS && period.get<double>() <= kMaxFramePeriodS)) {
    throw input_error(name, "frame_period_s: must be a number in [" +
                                number_text(kMinFramePeriodS) + ", " +
                                number_text(kMaxFramePeriodS) + "] s, got " + shown(period));
  }
  facts.frame_period_s = period.get<double>();
  facts.pulses = whole_number(required(summary, name, "pulses"), name, "pulses", 0,
                              static_cast<std::uint64_t>(facts.frames) * kMaxPulsesPerFrame);
  const Json& returns = required(summary, name, "returns");
  if (!returns.is_object()) {
    throw input_error(name, "returns: must be an object of counts by class, got " + shown(returns));
  }
  if (const auto noise = returns.find("noise"); noise != returns.end()) {
    facts.noise_returns =
        whole_number(*noise, name, "returns.noise", 0, facts.pulses * kMaxReturnsPerPulse);
  }
  return facts;
}

FlightFacts read_flight_facts(const std::filesystem::path& summary_json) {
  return parse_flight_facts(read_input_file(summary_json, "run summary", kMaxSummaryBytes),
                            summary_json.string());
}

}  // namespace owsim
