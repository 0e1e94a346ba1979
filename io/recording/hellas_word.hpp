#pragma once
// The HELLAS 32-bit data word (SENSOR-SPEC §8, source table 3), packed and unpacked bit-exactly.
//
// bit 31 Select · 30 ZT (line gate, active low: 0 on the last pulse of a line) · 29–16 time tag
// (14 bits, 0.5 ms per tick, cyclic) · 15 Ain · 14 NI · 13 MovDir · 12 BT (frame gate, active
// low) · 11–0 counter. On a header word (Select = 1) the 12 low bits hold the header β code
// instead of a count. Every bit belongs to a field, so unpack followed by pack reproduces any
// 32-bit value exactly. Words are stored little-endian on disk (io/recording/word_file.hpp).
#include <cstdint>

namespace owsim {

inline constexpr std::uint16_t kHellasTimeTagMax = 0x3FFF;  // 14-bit field

struct HellasWord {
  bool select = false;         // 1 on a header word: counter holds the header β code
  bool zt = true;              // line gate, active low
  std::uint16_t time_tag = 0;  // floor(t / 0.5 ms) mod 16384, 14 bits
  bool ain = false;            // square wave toggling at every line gate
  bool ni = false;             // encoder reference mark: the pulse nearest β = 0
  bool mov_dir = false;        // 0 while β increases, 1 while it decreases
  bool bt = true;              // frame gate, active low
  std::uint16_t counter = 0;   // 12 bits: the range count, or the header β code

  bool operator==(const HellasWord&) const = default;
};

// The 32-bit word  (SENSOR-SPEC §8, table 3). Throws owsim::Error when the time tag exceeds 14
// bits or the counter 12 bits.
[[nodiscard]] std::uint32_t pack(const HellasWord& word);
// The fields of a 32-bit word  (SENSOR-SPEC §8, table 3); total: every value decodes.
[[nodiscard]] HellasWord unpack_hellas(std::uint32_t bits);

}  // namespace owsim
