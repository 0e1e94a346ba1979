#pragma once
// The progress line of long work — `owsim run`, `owsim decode`, `owsim merge` (INTERFACE.md: frames
// done, pulses/s and ETA on a terminal; nothing when stderr is not a terminal or with --quiet).
// Redrawn in place at most every 250 ms, and once more, ending the line, when the last frame is
// done. The rate and ETA are from the wall time since construction and the work done since.
#include <chrono>
#include <cstdint>

namespace owsim::cli {

class ProgressLine {
 public:
  // `enabled`: the command was not asked to be quiet (the line shows only if stderr is a terminal
  // too). The work is frames 0 … frames − 1, of which those before `first` were done earlier (a
  // resumed run): they count toward neither the rate nor the ETA.
  ProgressLine(bool enabled, std::uint64_t frames, std::uint64_t first = 0);

  // Frames 0 … done − 1 are complete; `pulses` pulses have been processed since construction.
  void frame_done(std::uint64_t done, std::uint64_t pulses);

 private:
  using Clock = std::chrono::steady_clock;

  bool enabled_;
  std::uint64_t frames_;
  std::uint64_t first_;
  Clock::time_point start_;
  Clock::time_point last_;
};

}  // namespace owsim::cli
