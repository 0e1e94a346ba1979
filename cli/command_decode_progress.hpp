#pragma once
// The progress line of `owsim decode` and `owsim merge` (INTERFACE.md: long work shows frames done,
// pulses/s and ETA on a terminal, and stays quiet when stderr is not one or with --quiet).
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>

namespace owsim::cli {

class RecordingProgress {
 public:
  RecordingProgress(bool enabled, std::uint64_t frames)
      : enabled_(enabled && isatty(STDERR_FILENO) != 0), frames_(frames) {}

  void frame_done(std::uint64_t done, std::uint64_t pulses) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (done < frames_ && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? static_cast<double>(pulses) / elapsed : 0.0;
    const double eta =
        done > 0 ? elapsed * static_cast<double>(frames_ - done) / static_cast<double>(done) : 0.0;
    std::fprintf(stderr, "\rframe %llu/%llu  %.2f Mpulses/s  ETA %.0f s   ",
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(frames_),
                 rate / 1e6, eta);
    if (done == frames_) std::fprintf(stderr, "\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  std::uint64_t frames_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_ = start_;
};

}  // namespace owsim::cli
