// Protects the pinned HELLAS details of SENSOR-SPEC §8: the NI pulse, β reconstructed from NI and
// the mirror angle factor (eq 4.3), the Ain square wave across frame boundaries, the header code.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "geometry/error.hpp"
#include "sensor/hellas_scan.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

ScanParams hellas() {
  ScanParams p;
  p.model = SensorModel::hellas;
  return p;
}

TEST(HellasScan, MirrorAngleFactor) {
  ScanParams p = hellas();
  EXPECT_DOUBLE_EQ(hellas_mirror_angle_factor_deg(p), 36.0 / 20'352.0);
  EXPECT_NEAR(hellas_mirror_angle_factor_deg(p), 0.0017688679, 1e-10);
  p.hellas_mirror_angle_factor_deg = 0.002;
  EXPECT_EQ(hellas_mirror_angle_factor_deg(p), 0.002);
}

TEST(HellasScan, NiIsThePulseNearestZeroAndReconstructsBeta) {
  const ScanParams p = hellas();
  const double maf = hellas_mirror_angle_factor_deg(p);
  for (std::uint64_t seed : {0u, 1u, 2u}) {
    for (std::int64_t frame = 0; frame < 6; ++frame) {
      const FrameSweep sweep = frame_sweep(p, seed, frame);
      const int ni = hellas_ni_pulse(p, sweep);
      // Brute force: the pulse of least |mirror β|.
      int nearest = 0;
      for (int k = 1; k < p.pulses_per_frame(); ++k) {
        if (std::abs(mirror_beta_deg(p, sweep, k)) < std::abs(mirror_beta_deg(p, sweep, nearest))) {
          nearest = k;
        }
      }
      ASSERT_EQ(ni, nearest) << "seed " << seed << " frame " << frame;
      EXPECT_NEAR(ni, 10'176, 70);  // mid-frame, within the jitter's ±0.114° / MAF pulses
      const int mov_dir = pulse_of_frame(p, sweep, 0).mov_dir;
      const int direction = mov_dir == 0 ? 1 : -1;
      for (int k = 0; k < p.pulses_per_frame(); ++k) {
        const double truth = mirror_beta_deg(p, sweep, k);
        ASSERT_LE(std::abs(hellas_mirror_beta_deg(p, k, ni, direction) - truth), 0.5 * maf + 1e-12)
            << "seed " << seed << " frame " << frame << " pulse " << k;
      }
    }
  }
}

TEST(HellasScan, NiMissingWhenTheSweepDoesNotCrossZero) {
  ScanParams p = hellas();
  p.sweep_deg = 10.0;
  p.frame_jitter_deg = 0.0;
  const double maf = hellas_mirror_angle_factor_deg(p);
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 0, 5.0)), 0);               // β from 0 up
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 0, 5.0 + 0.25 * maf)), 0);  // within MAF/2
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 0, 5.0 + maf)), -1);        // beyond MAF/2
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 0, 10.0)), -1);
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 1, 10.0)), -1);
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 0, -10.0)), -1);
  // Falling frame: β from 10 − 0.75·MAF down to MAF/4 at the last pulse, which is nearest 0.
  const FrameSweep falling = frame_sweep(p, 0, 1, 5.0 - 0.75 * maf);
  EXPECT_NEAR(mirror_beta_deg(p, falling, p.pulses_per_frame() - 1), 0.25 * maf, 1e-12);
  EXPECT_EQ(hellas_ni_pulse(p, falling), p.pulses_per_frame() - 1);
  EXPECT_EQ(hellas_ni_pulse(p, frame_sweep(p, 0, 1, 5.0 + maf)), -1);  // ends at 2·MAF
}

TEST(HellasScan, ReconstructionFormula) {
  const ScanParams p = hellas();
  const double maf = 36.0 / 20'352.0;
  EXPECT_DOUBLE_EQ(hellas_mirror_beta_deg(p, 10'176, 10'176, 1), 0.0);
  EXPECT_DOUBLE_EQ(hellas_mirror_beta_deg(p, 10'276, 10'176, 1), 100 * maf);
  EXPECT_DOUBLE_EQ(hellas_mirror_beta_deg(p, 10'276, 10'176, -1), -100 * maf);
  EXPECT_DOUBLE_EQ(hellas_mirror_beta_deg(p, 0, 10'176, 1), -10'176 * maf);
}

TEST(HellasScan, AinTogglesAtEveryLineGateAcrossFrames) {
  const ScanParams p = hellas();
  EXPECT_FALSE(hellas_ain(p, 0, 0));
  EXPECT_FALSE(hellas_ain(p, 0, 127));
  EXPECT_TRUE(hellas_ain(p, 0, 128));
  EXPECT_FALSE(hellas_ain(p, 0, 20'351));  // line 158
  EXPECT_TRUE(hellas_ain(p, 1, 0));        // global line 159: the wave runs on
  bool previous_ain = hellas_ain(p, 0, 0);
  bool previous_gate = false;
  for (std::int64_t frame = 0; frame < 4; ++frame) {
    const FrameSweep sweep = frame_sweep(p, 0, frame);
    for (int k = 0; k < p.pulses_per_frame(); ++k) {
      const bool ain = hellas_ain(p, frame, k);
      if (frame > 0 || k > 0) {
        ASSERT_EQ(ain != previous_ain, previous_gate) << "frame " << frame << " pulse " << k;
      }
      previous_ain = ain;
      previous_gate = pulse_of_frame(p, sweep, k).line_gate;
    }
  }
  EXPECT_NE(hellas_ain(p, -1, 20'351), hellas_ain(p, 0, 0));
}

TEST(HellasScan, HeaderCodeValues) {
  EXPECT_EQ(hellas_header_beta_code(-18.0), 248);
  EXPECT_EQ(hellas_header_beta_code(0.0), 2'048);
  EXPECT_EQ(hellas_header_beta_code(18.0), 3'848);
  EXPECT_EQ(hellas_header_beta_code(-20.48), 0);
  EXPECT_EQ(hellas_header_beta_code(20.47), 4'095);
  EXPECT_EQ(hellas_header_beta_code(-18.004), 248);
  EXPECT_EQ(hellas_header_beta_code(-18.006), 247);
  EXPECT_EQ(hellas_header_beta_code(-25.0), 0);     // saturates
  EXPECT_EQ(hellas_header_beta_code(25.0), 4'095);  // saturates
  EXPECT_THROW((void)hellas_header_beta_code(std::nan("")), Error);
  EXPECT_DOUBLE_EQ(hellas_beta_from_header_code(248), -18.0);
}

TEST(HellasScan, HeaderCodeRoundTrip) {
  for (int code = 0; code <= 4'095; ++code) {
    const auto word = static_cast<std::uint16_t>(code);
    ASSERT_EQ(hellas_header_beta_code(hellas_beta_from_header_code(word)), word);
  }
  const ScanParams p = hellas();
  for (std::int64_t frame = 0; frame < 50; ++frame) {
    const double start = frame_sweep(p, 4, frame).mirror_beta_start_deg;
    ASSERT_NEAR(hellas_beta_from_header_code(hellas_header_beta_code(start)), start, 0.005 + 1e-12);
  }
}

}  // namespace
}  // namespace owsim
