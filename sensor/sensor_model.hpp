#pragma once
// The two sensors owsim simulates: MilOWS (64-bit words, motor encoder, scan rotated 90° about the
// forward axis) and its predecessor HELLAS (32-bit words, no encoder: β from the NI mark).
#include <optional>
#include <string_view>

namespace owsim {

enum class SensorModel { milows, hellas };

[[nodiscard]] constexpr std::string_view to_string(SensorModel model) {
  return model == SensorModel::milows ? "milows" : "hellas";
}
// The returns a pulse's word records (SENSOR-SPEC §8): MilOWS two (counter 1 and 2), HELLAS the
// first only. Point outputs hold exactly these, like the words' decode.
[[nodiscard]] constexpr int recorded_returns(SensorModel model) {
  return model == SensorModel::milows ? 2 : 1;
}
[[nodiscard]] constexpr std::optional<SensorModel> parse_sensor_model(std::string_view text) {
  if (text == "milows") return SensorModel::milows;
  if (text == "hellas") return SensorModel::hellas;
  return std::nullopt;
}

}  // namespace owsim
