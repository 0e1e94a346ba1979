#include "io/recording/frame_words.hpp"

#include <algorithm>
#include <array>

#include "geometry/error.hpp"
#include "io/recording/hellas_word.hpp"
#include "io/recording/milows_word.hpp"
#include "sensor/hellas_scan.hpp"

namespace owsim {
namespace {

void require_same_size(std::size_t pulses, std::size_t returns, std::size_t out) {
  if (pulses != returns || pulses != out) {
    throw Error("frame words: pulse, return and word buffers differ in size");
  }
}

}  // namespace

void pack_milows_frame(std::span<const Pulse> pulses, std::span<const PulseReturns> returns,
                       std::span<std::uint64_t> out) {
  require_same_size(pulses.size(), returns.size(), out.size());
  // The time tags of a block of pulses at once (vectorised), then the words.
  constexpr std::size_t kBlock = 256;
  std::array<double, kBlock> times;
  std::array<std::uint16_t, kBlock> tags;
  for (std::size_t first = 0; first < pulses.size(); first += kBlock) {
    const std::size_t n = std::min(kBlock, pulses.size() - first);
    for (std::size_t i = 0; i < n; ++i) times[i] = pulses[first + i].time_s;
    milows_time_tags(std::span(times.data(), n), std::span(tags.data(), n));
    for (std::size_t i = 0; i < n; ++i) {
      const Pulse& pulse = pulses[first + i];
      MilowsWord word;
      word.time_tag = tags[i];
      word.encoder = pulse.encoder;
      word.frame_gate = pulse.frame_gate;
      word.line_gate = pulse.line_gate;
      word.counter1 = returns[first + i].counter1;
      word.counter2 = returns[first + i].counter2;
      out[first + i] = pack(word);
    }
  }
}

void pack_hellas_frame(const ScanParams& scan, const FrameSweep& sweep,
                       std::span<const Pulse> pulses, std::span<const PulseReturns> returns,
                       std::span<std::uint32_t> out) {
  require_same_size(pulses.size(), returns.size(), out.size());
  const int ni_pulse = hellas_ni_pulse(scan, sweep);
  for (std::size_t k = 0; k < pulses.size(); ++k) {
    const Pulse& pulse = pulses[k];
    HellasWord word;
    word.zt = !pulse.line_gate;
    word.bt = !pulse.frame_gate;
    word.time_tag = hellas_time_tag(pulse.time_s);
    word.ain = hellas_ain(scan, sweep.frame, pulse.index);
    word.ni = pulse.index == ni_pulse;
    word.mov_dir = pulse.mov_dir != 0;
    word.counter = returns[k].counter1;
    out[k] = pack(word);
  }
}

std::uint32_t hellas_file_header_word(const FrameSweep& first_sweep, double time_s) {
  HellasWord word;
  word.select = true;
  word.time_tag = hellas_time_tag(time_s);
  word.mov_dir = first_sweep.direction < 0;
  word.counter = hellas_header_beta_code(first_sweep.mirror_beta_start_deg);
  return pack(word);
}

}  // namespace owsim
