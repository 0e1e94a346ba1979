#pragma once
// Test helper: correct MilOWS and HELLAS recordings, built bit by bit from SENSOR-SPEC §2/§8 here
// (not with owsim's codecs or writers), and written to disk byte by byte, little-endian.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sensor/motor_encoder.hpp"

namespace owsim::fixture {

inline constexpr int kFibers = 128;
inline constexpr int kLines = 159;
inline constexpr int kPulsesPerFrame = kFibers * kLines;  // 20,352
inline constexpr std::uint16_t kTimeout = 2066;
inline constexpr std::uint16_t kReferenceCounts = 10;
inline constexpr int kNiPulse = kPulsesPerFrame / 2;  // mirror β nearest 0 without jitter

// First return of fiber slot `slot` on global line `line`: a return on every third (line + slot).
inline std::uint16_t counter1(std::int64_t line, int slot) {
  if (slot == kFibers - 1) return kReferenceCounts;
  return (line + slot) % 3 == 0 ? static_cast<std::uint16_t>(100 + 7 * slot) : kTimeout;
}
// Second return: rarer, further.
inline std::uint16_t counter2(std::int64_t line, int slot) {
  if (slot == kFibers - 1) return kTimeout;
  return (7 * line + slot) % 11 == 0 ? static_cast<std::uint16_t>(1000 + slot) : kTimeout;
}

// Mirror β of pulse k in frame f: −18° → +18° on even frames, back on odd ones (§2 pinned sweep).
inline double mirror_beta_deg(std::int64_t frame, int pulse) {
  const double sign = frame % 2 == 0 ? 1.0 : -1.0;
  return sign * (-18.0 + 36.0 * pulse / kPulsesPerFrame);
}

// `frames` whole frames; `first_pulse_number` offsets the pulse clock (time tags) only.
inline std::vector<std::uint64_t> milows_words(int frames, std::int64_t first_pulse_number = 0) {
  std::vector<std::uint64_t> words;
  words.reserve(static_cast<std::size_t>(frames) * kPulsesPerFrame);
  for (std::int64_t f = 0; f < frames; ++f) {
    for (int k = 0; k < kPulsesPerFrame; ++k) {
      const std::int64_t n = first_pulse_number + f * kPulsesPerFrame + k;
      const auto tag =
          static_cast<std::uint64_t>((n * 10000 / 61111) % 65536);  // floor(t / 100 µs)
      const auto encoder =
          static_cast<std::uint16_t>(encoder_from_mirror_beta(mirror_beta_deg(f, k)));
      const int slot = k % kFibers;
      const std::int64_t line = f * kLines + k / kFibers;
      const bool fg = k == kPulsesPerFrame - 1;
      const bool lg = slot == kFibers - 1;
      words.push_back(tag << 48 | std::uint64_t{encoder} << 32 | std::uint64_t{fg} << 31 |
                      std::uint64_t{lg} << 30 | std::uint64_t{counter2(line, slot)} << 16 |
                      counter1(line, slot));
    }
  }
  return words;
}

inline std::uint32_t hellas_header(double beta_start_deg, std::uint32_t tag) {
  const auto code = static_cast<std::uint32_t>(std::lround((beta_start_deg + 20.48) / 0.01));
  return 1u << 31 | 1u << 30 | tag << 16 | 1u << 12 | code;
}

// A header word, then `frames` whole frames.
inline std::vector<std::uint32_t> hellas_words(int frames, std::int64_t first_pulse_number = 0) {
  std::vector<std::uint32_t> words;
  words.reserve(static_cast<std::size_t>(frames) * kPulsesPerFrame + 1);
  const auto first_tag = static_cast<std::uint32_t>((first_pulse_number * 2000 / 61111) % 16384);
  words.push_back(hellas_header(-18.0, first_tag));
  for (std::int64_t f = 0; f < frames; ++f) {
    for (int k = 0; k < kPulsesPerFrame; ++k) {
      const std::int64_t n = first_pulse_number + f * kPulsesPerFrame + k;
      const auto tag = static_cast<std::uint32_t>((n * 2000 / 61111) % 16384);  // floor(t / 0.5 ms)
      const int slot = k % kFibers;
      const std::int64_t line = f * kLines + k / kFibers;
      const bool zt = slot != kFibers - 1;       // active low
      const bool bt = k != kPulsesPerFrame - 1;  // active low
      const bool ain = (line & 1) != 0;          // toggles at every line gate
      const bool ni = k == kNiPulse;
      const bool mov_dir = f % 2 == 1;
      words.push_back(std::uint32_t{zt} << 30 | tag << 16 | std::uint32_t{ain} << 15 |
                      std::uint32_t{ni} << 14 | std::uint32_t{mov_dir} << 13 |
                      std::uint32_t{bt} << 12 | counter1(line, slot));
    }
  }
  return words;
}

template <typename Word>
void write_words(const std::filesystem::path& path, std::span<const Word> words) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  for (const Word word : words) {
    for (std::size_t i = 0; i < sizeof(Word); ++i) out.put(static_cast<char>(word >> (8 * i)));
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// A fresh, empty directory under the system temporary directory.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("owsim_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace owsim::fixture
