#pragma once
// The MilOWS 64-bit data word (SENSOR-SPEC §8, source table 4), packed and unpacked bit-exactly.
//
// bits 63–48 time tag (u16, 100 µs per tick, cyclic) · 47–32 motor encoder (i16) · 31 FG ·
// 30 LG · 29 crosstalk · 28 reserved · 27–16 counter 2 (u12) · 15–14 LUT · 13–12 trigger ·
// 11–0 counter 1 (u12). Every bit belongs to a field, so unpack followed by pack reproduces any
// 64-bit value exactly — merging into a recording keeps every bit it does not change. Words are
// stored little-endian on disk (io/recording/word_file.hpp).
#include <cstdint>

#include "io/recording/word_field.hpp"
#include "sensor/motor_encoder.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {

inline constexpr std::uint8_t kMilowsTwoBitMax = 3;  // LUT and trigger fields, 2 bits each

struct MilowsWord {
  std::uint16_t time_tag = 0;  // floor(t / 100 µs) mod 65536
  EncoderCount encoder = 0;    // motor angle, §3
  bool frame_gate = false;     // FG: last pulse of a frame
  bool line_gate = false;      // LG: last pulse of a line
  bool crosstalk = false;      // set by the hardware on optical crosstalk; 0 when simulated
  bool reserved28 = false;     // reserved, 0 when simulated
  std::uint16_t counter2 = 0;  // second return, 12 bits; timeout = none
  std::uint8_t lut = 0;        // reserved for LUT, 2 bits
  std::uint8_t trigger = 0;    // reserved for trigger, 2 bits
  std::uint16_t counter1 = 0;  // first return, 12 bits; timeout = none

  bool operator==(const MilowsWord&) const = default;
};

// Where each field sits in the word (table 4).
namespace milows_bits {
inline constexpr int kTimeTagShift = 48;
inline constexpr int kEncoderShift = 32;
inline constexpr int kFrameGateBit = 31;
inline constexpr int kLineGateBit = 30;
inline constexpr int kCrosstalkBit = 29;
inline constexpr int kReservedBit = 28;
inline constexpr int kCounter2Shift = 16;
inline constexpr int kLutShift = 14;
inline constexpr int kTriggerShift = 12;
inline constexpr std::uint64_t kCounterMask = 0xFFF;
inline constexpr std::uint64_t kTwoBitMask = 0x3;
}  // namespace milows_bits

// The 64-bit word  (SENSOR-SPEC §8, table 4). Throws owsim::Error when a counter exceeds 4095 or
// LUT/trigger exceeds 3. Inline: a frame packs one a pulse.
[[nodiscard]] inline std::uint64_t pack(const MilowsWord& word) {
  using namespace milows_bits;
  require_field_width("MilOWS", "counter 1", word.counter1, kCounterMax);
  require_field_width("MilOWS", "counter 2", word.counter2, kCounterMax);
  require_field_width("MilOWS", "LUT", word.lut, kMilowsTwoBitMax);
  require_field_width("MilOWS", "trigger", word.trigger, kMilowsTwoBitMax);
  const auto flag = [](bool value, int bit) { return static_cast<std::uint64_t>(value) << bit; };
  const auto encoder_bits = static_cast<std::uint16_t>(word.encoder);
  return static_cast<std::uint64_t>(word.time_tag) << kTimeTagShift |
         static_cast<std::uint64_t>(encoder_bits) << kEncoderShift |
         flag(word.frame_gate, kFrameGateBit) | flag(word.line_gate, kLineGateBit) |
         flag(word.crosstalk, kCrosstalkBit) | flag(word.reserved28, kReservedBit) |
         static_cast<std::uint64_t>(word.counter2) << kCounter2Shift |
         static_cast<std::uint64_t>(word.lut) << kLutShift |
         static_cast<std::uint64_t>(word.trigger) << kTriggerShift | word.counter1;
}
// The fields of a 64-bit word  (SENSOR-SPEC §8, table 4); total: every value decodes.
[[nodiscard]] MilowsWord unpack_milows(std::uint64_t bits);

}  // namespace owsim
