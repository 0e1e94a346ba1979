#include "io/recording/frame_words.hpp"

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
  for (std::size_t k = 0; k < pulses.size(); ++k) {
    const Pulse& pulse = pulses[k];
    MilowsWord word;
    word.time_tag = milows_time_tag(pulse.time_s);
    word.encoder = pulse.encoder;
    word.frame_gate = pulse.frame_gate;
    word.line_gate = pulse.line_gate;
    word.counter1 = returns[k].counter1;
    word.counter2 = returns[k].counter2;
    out[k] = pack(word);
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
