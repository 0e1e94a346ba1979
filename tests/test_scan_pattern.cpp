// Protects the MilOWS scan pattern of SENSOR-SPEC §2, §3, §8: pinned timing and sweep, frame
// jitter keyed by (seed, frame), sawtooth, gate flags, MovDir, encoder words, time tags, the
// look-into-turn clamp, and that any frame computed alone equals the same frame computed in turn.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <utility>
#include <vector>

#include "geometry/error.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/motor_encoder.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

constexpr double kJitter = 0.114248067;

TEST(ScanPattern, FrameSizeAndDuration) {
  const ScanParams p;
  EXPECT_EQ(p.pulses_per_frame(), 20'352);
  EXPECT_DOUBLE_EQ(p.frame_duration_s(), 20'352.0 / 61'111.0);
  EXPECT_NEAR(p.frame_duration_s(), 0.33304, 1e-5);
  EXPECT_EQ(pulse_time_s(p, 0, 0), 0.0);
  EXPECT_DOUBLE_EQ(pulse_time_s(p, 1, 0), 20'352.0 / 61'111.0);
  EXPECT_DOUBLE_EQ(pulse_time_s(p, 0, 20'351) + 1.0 / 61'111.0, pulse_time_s(p, 1, 0));
  EXPECT_EQ(pulse_time_s(p, 3, 55), 1.0);  // pulse 61,111 fires at exactly 1 s
  EXPECT_EQ(pulse_time_s(p, 100'000, 17), (100'000.0 * 20'352 + 17) / 61'111.0);
}

TEST(ScanPattern, PulseTimeHonoursStartAndRejectsOverflow) {
  ScanParams p;
  p.start_s = 12.5;
  EXPECT_DOUBLE_EQ(pulse_time_s(p, 2, 7), 12.5 + (2 * 20'352 + 7) / 61'111.0);
  EXPECT_THROW((void)pulse_time_s(p, INT64_MAX / 1000, 0), Error);
}

TEST(ScanPattern, FrameZeroSweepsUpFromMinusEighteen) {
  const ScanParams p;
  for (std::uint64_t seed : {0u, 1u, 77u}) {
    const FrameSweep sweep = frame_sweep(p, seed, 0);
    EXPECT_EQ(sweep.direction, 1);
    EXPECT_EQ(sweep.start_s, 0.0);
    EXPECT_NEAR(mirror_beta_deg(p, sweep, 0), -18.0, 0.1143);
    EXPECT_NEAR(mirror_beta_deg(p, sweep, 20'351) - mirror_beta_deg(p, sweep, 0),
                36.0 * 20'351.0 / 20'352.0, 1e-12);
    for (int k = 0; k < 20'352; k += 97) {
      EXPECT_NEAR(mirror_beta_deg(p, sweep, k), sweep.mirror_beta_start_deg + 36.0 * k / 20'352,
                  1e-12);
    }
  }
}

TEST(ScanPattern, FrameOneFalls) {
  const ScanParams p;
  const FrameSweep sweep = frame_sweep(p, 0, 1);
  EXPECT_EQ(sweep.direction, -1);
  EXPECT_DOUBLE_EQ(sweep.start_s, 20'352.0 / 61'111.0);
  EXPECT_NEAR(mirror_beta_deg(p, sweep, 0), 18.0, 0.1143);
  EXPECT_NEAR(mirror_beta_deg(p, sweep, 20'351) - mirror_beta_deg(p, sweep, 0),
              -36.0 * 20'351.0 / 20'352.0, 1e-12);
  for (int k = 1; k < 20'352; ++k) {
    ASSERT_LT(mirror_beta_deg(p, sweep, k), mirror_beta_deg(p, sweep, k - 1));
  }
  EXPECT_EQ(frame_sweep(p, 0, 2).direction, 1);
  EXPECT_EQ(frame_sweep(p, 0, -1).direction, -1);
}

TEST(ScanPattern, PulseFieldsOfAWholeFrame) {
  const ScanParams p;
  for (std::int64_t frame : {0, 1}) {
    const FrameSweep sweep = frame_sweep(p, 5, frame);
    int frame_gates = 0, line_gates = 0;
    for (int k = 0; k < p.pulses_per_frame(); ++k) {
      const Pulse pulse = pulse_of_frame(p, sweep, k);
      ASSERT_EQ(pulse.index, k);
      ASSERT_EQ(pulse.line, k / 128);
      ASSERT_EQ(pulse.slot, k % 128);
      ASSERT_EQ(pulse.fiber, k % 128 + 1);
      ASSERT_EQ(pulse.reference, pulse.fiber == 128);
      ASSERT_EQ(pulse.time_s, pulse_time_s(p, frame, k));
      if (pulse.reference) {
        ASSERT_TRUE(std::isnan(pulse.alpha_deg));
      } else {
        ASSERT_EQ(pulse.alpha_deg, fiber_alpha_deg(p, pulse.fiber));
      }
      ASSERT_EQ(pulse.mirror_beta_deg, mirror_beta_deg(p, sweep, k));
      // β_FC: −0.134° on odd fibers, +0.134° on even ones, so it alternates pulse by pulse.
      ASSERT_NEAR(pulse.beta_deg - pulse.mirror_beta_deg, pulse.fiber % 2 ? -0.134 : 0.134, 1e-12);
      ASSERT_EQ(pulse.encoder, encoder_from_mirror_beta(pulse.mirror_beta_deg));
      ASSERT_EQ(pulse.mov_dir, frame == 0 ? 0 : 1);
      ASSERT_EQ(pulse.frame_gate, k == 20'351) << k;
      ASSERT_EQ(pulse.line_gate, k % 128 == 127) << k;
      frame_gates += pulse.frame_gate;
      line_gates += pulse.line_gate;
    }
    EXPECT_EQ(frame_gates, 1);
    EXPECT_EQ(line_gates, 159);
  }
}

TEST(ScanPattern, EncoderFollowsTheMirrorAndIsZeroForHellas) {
  ScanParams p;
  const FrameSweep sweep = frame_sweep(p, 0, 0);
  // β rises, φ falls: the encoder word never increases over an upward sweep.
  EncoderCount previous = pulse_of_frame(p, sweep, 0).encoder;
  for (int k = 1; k < p.pulses_per_frame(); ++k) {
    const EncoderCount now = pulse_of_frame(p, sweep, k).encoder;
    ASSERT_LE(now, previous);
    previous = now;
  }
  p.model = SensorModel::hellas;
  for (int k = 0; k < p.pulses_per_frame(); k += 101) {
    ASSERT_EQ(pulse_of_frame(p, sweep, k).encoder, 0);
  }
}

TEST(ScanPattern, ReferenceFiberPulsesAreFilled) {
  const ScanParams p;
  const Pulse pulse = pulse_of_frame(p, frame_sweep(p, 0, 0), 127);
  EXPECT_TRUE(pulse.reference);
  EXPECT_EQ(pulse.fiber, 128);
  EXPECT_TRUE(std::isnan(pulse.alpha_deg));
  EXPECT_TRUE(std::isfinite(pulse.beta_deg));
  EXPECT_NE(pulse.encoder, 0);
  EXPECT_TRUE(pulse.line_gate);
}

TEST(ScanPattern, SequentialOrderReachesThePulse) {
  ScanParams p;
  p.fiber_order = FiberOrder::sequential;
  const FrameSweep sweep = frame_sweep(p, 0, 0);
  EXPECT_EQ(pulse_of_frame(p, sweep, 64).fiber, 127);
  EXPECT_EQ(pulse_of_frame(p, sweep, 64).alpha_deg, 0.0);
  EXPECT_EQ(pulse_of_frame(p, sweep, 128 + 126).fiber, 65);
  EXPECT_EQ(pulse_of_frame(p, sweep, 128 + 126).alpha_deg, 21.0);
}

TEST(ScanPattern, PulseOutsideTheFrameThrows) {
  const ScanParams p;
  const FrameSweep sweep = frame_sweep(p, 0, 0);
  EXPECT_THROW((void)pulse_of_frame(p, sweep, -1), Error);
  EXPECT_THROW((void)pulse_of_frame(p, sweep, 20'352), Error);
}

// Pulse n (global) fires at n / 61,111 s: tick = floor(n · 10,000 / 61,111), exactly.
TEST(ScanPattern, TimeTagsMatchIntegerArithmetic) {
  ScanParams p;
  for (std::int64_t frame : {0, 1, 2, 3, 17, 1'000, 100'000, 400'000}) {
    for (int k = 0; k < p.pulses_per_frame(); ++k) {
      const std::int64_t n = frame * 20'352 + k;
      const double t = pulse_time_s(p, frame, k);
      ASSERT_EQ(milows_time_tag(t), (n * 10'000 / 61'111) % 65'536)
          << "frame " << frame << " " << k;
      ASSERT_EQ(hellas_time_tag(t), (n * 2'000 / 61'111) % 16'384) << "frame " << frame << " " << k;
    }
  }
}

TEST(ScanPattern, TimeTagsWithAStartTime) {
  ScanParams p;
  p.start_s = 0.57;  // 0.57 · 10,000 = 5699.999999999999 in doubles: floor alone gives 5699
  for (std::int64_t frame : {0, 5}) {
    for (int k = 0; k < p.pulses_per_frame(); ++k) {
      const std::int64_t n = frame * 20'352 + k;
      const double t = pulse_time_s(p, frame, k);
      ASSERT_EQ(milows_time_tag(t), (5'700 + n * 10'000 / 61'111) % 65'536) << k;
      ASSERT_EQ(hellas_time_tag(t), (1'140 + n * 2'000 / 61'111) % 16'384) << k;
    }
  }
}

TEST(ScanPattern, TimeTagBoundariesAndWrap) {
  EXPECT_EQ(milows_time_tag(0.0), 0);
  EXPECT_EQ(milows_time_tag(0.3), 3'000);
  EXPECT_EQ(milows_time_tag(0.57), 5'700);  // 0.57 · 10,000 = 5699.999999999999 in doubles
  EXPECT_EQ(milows_time_tag(0.0003), 3);    // 0.0003 · 10,000 = 2.9999999999999996
  EXPECT_EQ(milows_time_tag(100.57), 1'005'700 % 65'536);
  EXPECT_EQ(milows_time_tag(0.00009999), 0);
  EXPECT_EQ(milows_time_tag(6.5535), 65'535);
  EXPECT_EQ(milows_time_tag(6.5536), 0);
  EXPECT_EQ(milows_time_tag(6.5537), 1);
  EXPECT_EQ(milows_time_tag(-0.00005), 65'535);
  EXPECT_EQ(hellas_time_tag(0.0005), 1);
  EXPECT_EQ(hellas_time_tag(0.00049), 0);
  EXPECT_EQ(hellas_time_tag(8.1915), 16'383);
  EXPECT_EQ(hellas_time_tag(8.192), 0);
  EXPECT_EQ(hellas_time_tag(3600.0), 7'200'000 % 16'384);
  EXPECT_THROW((void)milows_time_tag(std::nan("")), Error);
  EXPECT_THROW((void)hellas_time_tag(INFINITY), Error);
}

// The tags are taken in integers below 2^62 ticks and with fmod above: both give the tick count
// modulo the tag range, for times from microseconds to far beyond any flight.
TEST(ScanPattern, TimeTagsAreTheTickCountModuloTheRangeAtAnyMagnitude) {
  for (const double t :
       {1e-5, 0.12345, 3.3e3, 7.7e7, 1.23456789e11, -2.5e13, 4.0e14, 3.0e15, -6.0e16, 1.0e20}) {
    for (const auto& [ticks_per_s, modulus] :
         {std::pair{1e4, 65'536.0}, std::pair{2e3, 16'384.0}}) {
      const double ticks = t * ticks_per_s;
      double want = std::fmod(std::floor(ticks + std::abs(ticks) * 1e-14), modulus);
      if (want < 0) want += modulus;
      const std::uint16_t got = modulus == 65'536.0 ? milows_time_tag(t) : hellas_time_tag(t);
      EXPECT_EQ(got, static_cast<std::uint16_t>(want)) << t;
    }
  }
}

// milows_time_tags (the words' vectorised tags) gives milows_time_tag's value for every time: a
// whole flight's pulse times, ticks and their neighbours a hair either side, −0, negative times,
// every magnitude up to and beyond 2^62 ticks, blocks not a multiple of the lanes; throws where it
// throws.
TEST(ScanPattern, TimeTagsOverArraysAreTheTimeTags) {
  std::vector<double> times;
  const ScanParams p;
  for (std::int64_t frame : {0, 1, 400'000}) {
    for (int k = 0; k < p.pulses_per_frame(); ++k) times.push_back(pulse_time_s(p, frame, k));
  }
  for (std::int64_t tick = -70'000; tick < 140'000; tick += 7) {
    const double t = static_cast<double>(tick) * 1e-4;
    times.insert(times.end(), {t, std::nextafter(t, -INFINITY), std::nextafter(t, INFINITY)});
  }
  times.insert(times.end(), {0.0, -0.0, 0.57, 0.0003, 100.57, 6.5536, -0.00005, 1e-300, -1e-300});
  for (double t = 1e-6; t < 1e22; t *= 1.37) times.insert(times.end(), {t, -t});
  const double edge = 0x1p62 * 1e-4;  // 2^62 ticks
  for (const double t : {edge, -edge, std::nextafter(edge, 0.0), std::nextafter(edge, INFINITY)}) {
    times.push_back(t);
  }
  while (times.size() % 256 != 253) times.push_back(0.5);  // a last block of 253
  std::vector<std::uint16_t> tags(times.size());
  milows_time_tags(times, tags);
  for (std::size_t i = 0; i < times.size(); ++i) {
    ASSERT_EQ(tags[i], milows_time_tag(times[i])) << "t = " << times[i];
  }
  std::vector<double> bad(300, 1.0);
  bad[257] = std::nan("");
  std::vector<std::uint16_t> bad_tags(bad.size());
  EXPECT_THROW(milows_time_tags(bad, bad_tags), Error);
  bad[257] = -INFINITY;
  EXPECT_THROW(milows_time_tags(bad, bad_tags), Error);
  EXPECT_THROW(milows_time_tags(bad, std::span(bad_tags).first(3)), Error);
}

TEST(ScanPattern, JitterIsKeyedBySeedAndFrame) {
  const ScanParams p;
  std::set<double> starts;
  double low = 1.0, high = -1.0, sum = 0.0;
  constexpr int kFrames = 2'000;
  for (std::uint64_t seed : {0u, 1u}) {
    for (std::int64_t frame = 0; frame < kFrames; ++frame) {
      const FrameSweep sweep = frame_sweep(p, seed, frame);
      ASSERT_EQ(sweep.mirror_beta_start_deg, frame_sweep(p, seed, frame).mirror_beta_start_deg);
      const double jitter = sweep.mirror_beta_start_deg + 18.0 * sweep.direction;
      ASSERT_GE(jitter, -kJitter);
      ASSERT_LT(jitter, kJitter);
      low = std::min(low, jitter);
      high = std::max(high, jitter);
      sum += jitter;
      starts.insert(sweep.mirror_beta_start_deg);
    }
  }
  EXPECT_EQ(starts.size(), 2u * kFrames);  // no two (seed, frame) share a jitter
  EXPECT_LT(low, -0.99 * kJitter);
  EXPECT_GT(high, 0.99 * kJitter);
  // U(−1,1)·J over 4000 frames: mean 0 with sd J/√(3·4000).
  EXPECT_NEAR(sum / (2 * kFrames), 0.0, 4.0 * kJitter / std::sqrt(3.0 * 2 * kFrames));

  ScanParams still = p;
  still.frame_jitter_deg = 0.0;
  EXPECT_EQ(frame_sweep(still, 9, 0).mirror_beta_start_deg, -18.0);
  EXPECT_EQ(frame_sweep(still, 9, 1).mirror_beta_start_deg, 18.0);
}

bool same_pulse(const Pulse& a, const Pulse& b) {
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  return a.index == b.index && a.line == b.line && a.slot == b.slot && a.fiber == b.fiber &&
         a.reference == b.reference && same(a.time_s, b.time_s) && same(a.alpha_deg, b.alpha_deg) &&
         same(a.mirror_beta_deg, b.mirror_beta_deg) && same(a.beta_deg, b.beta_deg) &&
         a.encoder == b.encoder && a.frame_gate == b.frame_gate && a.line_gate == b.line_gate &&
         a.mov_dir == b.mov_dir;
}

TEST(ScanPattern, AFrameAloneEqualsTheFrameInSequence) {
  const ScanParams p;
  constexpr std::int64_t kTarget = 7;
  std::vector<Pulse> alone;
  const FrameSweep alone_sweep = frame_sweep(p, 11, kTarget, 3.5);
  for (int k = 0; k < p.pulses_per_frame(); ++k) alone.push_back(pulse_of_frame(p, alone_sweep, k));

  for (std::int64_t frame = 0; frame <= kTarget; ++frame) {
    const FrameSweep sweep = frame_sweep(p, 11, frame, 3.5);
    for (int k = 0; k < p.pulses_per_frame(); ++k) {
      const Pulse pulse = pulse_of_frame(p, sweep, k);
      if (frame == kTarget) ASSERT_TRUE(same_pulse(pulse, alone[static_cast<std::size_t>(k)])) << k;
    }
  }
}

TEST(ScanPattern, LookIntoTurnClamp) {
  ScanParams p;
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(p, 3.0), 6.0);
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(p, -2.5), -5.0);
  // The 12° limit would take the jittered sweep to 30.114°: the ±30° stop wins, 30 − 18 − J.
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(p, 10.0), 30.0 - 18.0 - kJitter);
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(p, -10.0), -(30.0 - 18.0 - kJitter));
  ScanParams narrow = p;  // a 20° sweep leaves room for the full 12° limit
  narrow.sweep_deg = 20.0;
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(narrow, 10.0), 12.0);
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(narrow, -7.0), -12.0);
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(narrow, 5.5), 11.0);
  EXPECT_EQ(look_into_turn_shift_deg(p, 0.0), 0.0);
  EXPECT_THROW((void)look_into_turn_shift_deg(p, std::nan("")), Error);

  ScanParams wide = p;  // a 50° sweep leaves only 30 − 25 − jitter for the shift
  wide.sweep_deg = 50.0;
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(wide, 10.0), 30.0 - 25.0 - kJitter);
  EXPECT_DOUBLE_EQ(look_into_turn_shift_deg(wide, -10.0), -(30.0 - 25.0 - kJitter));

  ScanParams off = p;
  off.look_into_turn_s = 0.0;
  EXPECT_EQ(look_into_turn_shift_deg(off, 10.0), 0.0);
  ScanParams hellas = p;
  hellas.model = SensorModel::hellas;
  EXPECT_EQ(look_into_turn_shift_deg(hellas, 10.0), 0.0);
}

TEST(ScanPattern, ShiftedSweepStaysWithinThirtyDegrees) {
  ScanParams p;
  p.sweep_deg = 50.0;
  for (double shift : {-40.0, -12.0, 12.0, 40.0}) {
    for (std::int64_t frame = 0; frame < 200; ++frame) {
      const FrameSweep sweep = frame_sweep(p, 3, frame, shift);
      ASSERT_LE(std::abs(sweep.centre_shift_deg), 30.0 - 25.0 - kJitter + 1e-12);
      ASSERT_LE(std::abs(mirror_beta_deg(p, sweep, 0)), kMirrorBetaLimitDeg);
      ASSERT_LE(std::abs(mirror_beta_deg(p, sweep, p.pulses_per_frame() - 1)), kMirrorBetaLimitDeg);
    }
  }
  const ScanParams defaults;
  const FrameSweep shifted = frame_sweep(defaults, 0, 0, 10.0);
  EXPECT_EQ(shifted.centre_shift_deg, 10.0);
  EXPECT_NEAR(mirror_beta_deg(defaults, shifted, 0), -8.0, 0.1143);
  EXPECT_NEAR(mirror_beta_deg(defaults, shifted, 20'351), 28.0, 0.1143);
  EXPECT_DOUBLE_EQ(frame_sweep(defaults, 0, 0, 12.0).centre_shift_deg, 30.0 - 18.0 - kJitter);
  EXPECT_THROW((void)frame_sweep(defaults, 0, 0, INFINITY), Error);
}

}  // namespace
}  // namespace owsim
