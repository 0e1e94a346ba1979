#include "sensor/irs_error.hpp"

#include "geometry/keyed_random.hpp"

namespace owsim {
namespace {

struct ChannelSpread {
  double sigma = 0;
  double bias = 0;
};

ChannelSpread spread(const IrsErrorModel& model, IrsChannel channel) {
  switch (channel) {
    case IrsChannel::heading:
      return {model.heading_sigma_deg, model.heading_bias_deg};
    case IrsChannel::roll:
    case IrsChannel::pitch:
      return {model.attitude_sigma_deg, model.attitude_bias_deg};
    case IrsChannel::velocity_north:
    case IrsChannel::velocity_east:
    case IrsChannel::velocity_up:
      return {model.velocity_sigma_mps, model.velocity_bias_mps};
  }
  return {};
}

}  // namespace

double irs_bias(const IrsErrorModel& model, std::uint64_t seed, IrsChannel channel) {
  const RandomKey key{seed, static_cast<std::int64_t>(channel), 0, RandomPurpose::irs_bias};
  return spread(model, channel).bias * standard_normal(key);
}

double irs_error(const IrsErrorModel& model, std::uint64_t seed, IrsChannel channel,
                 std::int64_t record) {
  const RandomKey key{seed, static_cast<std::int64_t>(channel), record, RandomPurpose::irs_error};
  return irs_bias(model, seed, channel) + spread(model, channel).sigma * standard_normal(key);
}

void add_irs_attitude_error(const IrsErrorModel& model, std::uint64_t seed,
                            std::vector<Attitude>& attitudes) {
  for (std::size_t i = 0; i < attitudes.size(); ++i) {
    const auto record = static_cast<std::int64_t>(i);
    attitudes[i].heading_deg += irs_error(model, seed, IrsChannel::heading, record);
    attitudes[i].roll_deg += irs_error(model, seed, IrsChannel::roll, record);
    attitudes[i].pitch_deg += irs_error(model, seed, IrsChannel::pitch, record);
  }
}

}  // namespace owsim
