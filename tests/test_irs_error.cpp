// Protects the IRS error model of SENSOR-SPEC §5 table 2: per-channel σ and per-flight bias of
// the stated sizes, keyed by (seed, channel, record) so the same seed gives the same errors, and
// applied to the trajectory's attitude only when asked.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "sensor/irs_error.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {
namespace {

const LocalFrame kFrame(Geodetic{48.6881, 10.8447, 450.0});

struct Moments {
  double mean = 0;
  double sigma = 0;
};

Moments moments(const std::vector<double>& values) {
  Moments m;
  for (double v : values) m.mean += v;
  m.mean /= double(values.size());
  for (double v : values) m.sigma += (v - m.mean) * (v - m.mean);
  m.sigma = std::sqrt(m.sigma / double(values.size() - 1));
  return m;
}

// Level flight east, constant attitude, 100 Hz.
NavTrack steady_track(std::size_t records) {
  NavTrack track;
  for (std::size_t i = 0; i < records; ++i) {
    track.time_s.push_back(0.01 * double(i));
    track.position_enu_m.emplace_back(0.4 * double(i), 0.0, 150.0);
    track.attitude.push_back({2.0, -1.0, 100.0});
  }
  return track;
}

TrajectoryOptions options_with_noise(bool on, std::uint64_t seed) {
  TrajectoryOptions options;
  options.smoothing = {1, 0};  // see the raw errors
  options.irs_noise = on;
  options.seed = seed;
  return options;
}

TEST(IrsError, TableTwoDefaults) {
  const IrsErrorModel model;
  EXPECT_EQ(model.heading_sigma_deg, 0.20);
  EXPECT_EQ(model.heading_bias_deg, 0.02);
  EXPECT_EQ(model.attitude_sigma_deg, 0.16);
  EXPECT_EQ(model.attitude_bias_deg, 0.05);
  EXPECT_EQ(model.velocity_sigma_mps, 0.23);
  EXPECT_EQ(model.velocity_bias_mps, 0.08);
}

TEST(IrsError, OffLeavesTheTrackUnchanged) {
  const NavTrack track = steady_track(1000);
  const Trajectory trajectory(track, kFrame, options_with_noise(false, 7));
  const std::vector<Pose> knots = trajectory.knots();
  for (std::size_t i = 0; i < knots.size(); ++i) {
    EXPECT_EQ(knots[i].attitude.roll_deg, 2.0);
    EXPECT_EQ(knots[i].attitude.pitch_deg, -1.0);
    EXPECT_EQ(knots[i].attitude.heading_deg, 100.0);
    EXPECT_EQ(knots[i].position_enu_m, track.position_enu_m[i]);
  }
}

TEST(IrsError, SigmaAndBiasPerChannelOverALongTrack) {
  const std::size_t n = 200'000;
  const std::uint64_t seed = 2024;
  const Trajectory trajectory(steady_track(n), kFrame, options_with_noise(true, seed));
  std::vector<double> heading, roll, pitch;
  for (const Pose& knot : trajectory.knots()) {
    heading.push_back(wrap_180_deg(knot.attitude.heading_deg - 100.0));
    roll.push_back(knot.attitude.roll_deg - 2.0);
    pitch.push_back(knot.attitude.pitch_deg + 1.0);
    EXPECT_EQ(knot.position_enu_m.z(), 150.0);  // positions are left alone
  }
  const IrsErrorModel model;
  // σ's relative standard error is 1/√(2n) = 0.16 %: allow 1 %. The mean's is σ/√n: allow 5×.
  const Moments h = moments(heading), r = moments(roll), p = moments(pitch);
  EXPECT_NEAR(h.sigma, 0.20, 0.002);
  EXPECT_NEAR(r.sigma, 0.16, 0.0016);
  EXPECT_NEAR(p.sigma, 0.16, 0.0016);
  EXPECT_NEAR(h.mean, irs_bias(model, seed, IrsChannel::heading), 5 * 0.20 / std::sqrt(double(n)));
  EXPECT_NEAR(r.mean, irs_bias(model, seed, IrsChannel::roll), 5 * 0.16 / std::sqrt(double(n)));
  EXPECT_NEAR(p.mean, irs_bias(model, seed, IrsChannel::pitch), 5 * 0.16 / std::sqrt(double(n)));
  // Channels draw independently.
  double covariance = 0.0;
  for (std::size_t i = 0; i < n; ++i) covariance += (heading[i] - h.mean) * (roll[i] - r.mean);
  EXPECT_LT(std::abs(covariance / double(n) / (h.sigma * r.sigma)), 0.01);
}

TEST(IrsError, BiasesSpreadAsTableTwoAcrossFlights) {
  const IrsErrorModel model;
  std::vector<double> heading, roll, pitch, velocity;
  for (std::uint64_t seed = 0; seed < 20'000; ++seed) {
    heading.push_back(irs_bias(model, seed, IrsChannel::heading));
    roll.push_back(irs_bias(model, seed, IrsChannel::roll));
    pitch.push_back(irs_bias(model, seed, IrsChannel::pitch));
    velocity.push_back(irs_bias(model, seed, IrsChannel::velocity_east));
  }
  // 20,000 flights: σ known to 0.5 %; allow 3 %.
  EXPECT_NEAR(moments(heading).sigma, 0.02, 0.0006);
  EXPECT_NEAR(moments(roll).sigma, 0.05, 0.0015);
  EXPECT_NEAR(moments(pitch).sigma, 0.05, 0.0015);
  EXPECT_NEAR(moments(velocity).sigma, 0.08, 0.0024);
  EXPECT_NEAR(moments(heading).mean, 0.0, 5 * 0.02 / std::sqrt(20'000.0));
  EXPECT_NE(roll[5], pitch[5]);  // each channel its own bias
}

TEST(IrsError, VelocityChannelsHaveTableTwoSigma) {
  const IrsErrorModel model;
  std::vector<double> north;
  for (std::int64_t record = 0; record < 100'000; ++record) {
    north.push_back(irs_error(model, 3, IrsChannel::velocity_north, record));
  }
  EXPECT_NEAR(moments(north).sigma, 0.23, 0.0023 * 2);
  EXPECT_NEAR(moments(north).mean, irs_bias(model, 3, IrsChannel::velocity_north),
              5 * 0.23 / std::sqrt(1e5));
}

TEST(IrsError, SameSeedSameErrorsOtherSeedOthers) {
  const Trajectory a(steady_track(500), kFrame, options_with_noise(true, 11));
  const Trajectory b(steady_track(500), kFrame, options_with_noise(true, 11));
  const Trajectory c(steady_track(500), kFrame, options_with_noise(true, 12));
  const std::vector<Pose> ka = a.knots(), kb = b.knots(), kc = c.knots();
  std::size_t differ = 0;
  for (std::size_t i = 0; i < ka.size(); ++i) {
    EXPECT_EQ(ka[i].attitude.heading_deg, kb[i].attitude.heading_deg);
    EXPECT_EQ(ka[i].attitude.roll_deg, kb[i].attitude.roll_deg);
    if (ka[i].attitude.heading_deg != kc[i].attitude.heading_deg) ++differ;
  }
  EXPECT_EQ(differ, ka.size());
  // A record's error depends on its index only, not on how many records precede it.
  const IrsErrorModel model;
  std::vector<Attitude> attitudes(10);
  add_irs_attitude_error(model, 11, attitudes);
  EXPECT_EQ(attitudes[7].heading_deg, irs_error(model, 11, IrsChannel::heading, 7));
  EXPECT_EQ(attitudes[7].pitch_deg, irs_error(model, 11, IrsChannel::pitch, 7));
  EXPECT_NEAR(wrap_180_deg(ka[7].attitude.heading_deg - 100.0),
              irs_error(model, 11, IrsChannel::heading, 7), 1e-12);
}

TEST(IrsError, ZeroModelAddsNothing) {
  const IrsErrorModel zero{0, 0, 0, 0, 0, 0};
  std::vector<Attitude> attitudes(100, Attitude{1, 2, 3});
  add_irs_attitude_error(zero, 5, attitudes);
  for (const Attitude& attitude : attitudes) {
    EXPECT_EQ(attitude.roll_deg, 1.0);
    EXPECT_EQ(attitude.heading_deg, 3.0);
  }
}

}  // namespace
}  // namespace owsim
