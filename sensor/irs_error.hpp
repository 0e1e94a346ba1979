#pragma once
// The IRS (inertial reference system) error model of SENSOR-SPEC §5, source table 2.
//
// Each channel's error = per-flight bias + per-record noise, both Gaussian and zero-mean:
// bias ~ N(0, bias²) drawn once per flight, noise ~ N(0, σ²) drawn per record. Table 2: heading
// σ 0.20° bias 0.02°; roll and pitch σ 0.16° bias 0.05°; velocity σ 0.23 m/s bias 0.08 m/s.
// Draws are keyed (geometry/keyed_random.hpp) so any record's error is a pure function of
// (seed, channel, record): noise by RandomKey{seed, frame = channel, pulse = record, irs_error},
// bias by RandomKey{seed, frame = channel, pulse = 0, irs_bias}.
// Velocity: the trajectory carries no velocities, and a GNSS-aided IRS's position does not
// integrate its velocity error, so the velocity channels are drawn only on request (for a
// consumer that models velocities); positions are left alone.
#include <cstdint>
#include <vector>

#include "geometry/rotation.hpp"

namespace owsim {

struct IrsErrorModel {
  double heading_sigma_deg = 0.20;   // table 2
  double heading_bias_deg = 0.02;    // table 2
  double attitude_sigma_deg = 0.16;  // roll and pitch, table 2
  double attitude_bias_deg = 0.05;   // roll and pitch, table 2
  double velocity_sigma_mps = 0.23;  // table 2
  double velocity_bias_mps = 0.08;   // table 2
};

// The channels of table 2; the value is the RandomKey frame.
enum class IrsChannel : std::int64_t {
  heading = 0,
  roll = 1,
  pitch = 2,
  velocity_north = 3,
  velocity_east = 4,
  velocity_up = 5,
};

// The channel's per-flight bias, bias · N(0, 1)  (SENSOR-SPEC §5, table 2)
[[nodiscard]] double irs_bias(const IrsErrorModel& model, std::uint64_t seed, IrsChannel channel);
// The channel's error at one record, bias + σ · N(0, 1) (degrees or m/s)  (SENSOR-SPEC §5, table 2)
[[nodiscard]] double irs_error(const IrsErrorModel& model, std::uint64_t seed, IrsChannel channel,
                               std::int64_t record);
// Adds the heading, roll and pitch errors to record i's attitude, i = index in the vector.
void add_irs_attitude_error(const IrsErrorModel& model, std::uint64_t seed,
                            std::vector<Attitude>& attitudes);

}  // namespace owsim
