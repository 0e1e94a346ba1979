#include "cli/progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace owsim::cli {

ProgressLine::ProgressLine(bool enabled, std::uint64_t frames, std::uint64_t first)
    : enabled_(enabled && isatty(STDERR_FILENO) != 0),
      frames_(frames),
      first_(first),
      start_(Clock::now()),
      last_(start_) {}

void ProgressLine::frame_done(std::uint64_t done, std::uint64_t pulses) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (done < frames_ && now - last_ < std::chrono::milliseconds(250)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(pulses) / elapsed : 0.0;
  const std::uint64_t since_start = done > first_ ? done - first_ : 0;
  const double eta = since_start > 0 ? elapsed * static_cast<double>(frames_ - done) /
                                           static_cast<double>(since_start)
                                     : 0.0;
  std::fprintf(stderr, "\rframe %llu/%llu  %.2f Mpulses/s  ETA %.0f s   ",
               static_cast<unsigned long long>(done), static_cast<unsigned long long>(frames_),
               rate / 1e6, eta);
  if (done == frames_) std::fprintf(stderr, "\n");
}

}  // namespace owsim::cli
