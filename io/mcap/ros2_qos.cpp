#include "io/mcap/ros2_qos.hpp"

namespace owsim::ros2 {
namespace {

// rmw_qos_*_policy_t
constexpr int kHistoryKeepLast = 1;
constexpr int kReliabilityReliable = 1;
constexpr int kDurabilityTransientLocal = 1;
constexpr int kDurabilityVolatile = 2;
constexpr int kLivelinessAutomatic = 1;

}  // namespace

std::string offered_qos_profiles(bool latched) {
  const std::string zero_duration = ":\n    sec: 0\n    nsec: 0\n";
  std::string yaml = "- history: " + std::to_string(kHistoryKeepLast) + "\n";
  yaml += "  depth: " + std::to_string(latched ? 1 : 10) + "\n";
  yaml += "  reliability: " + std::to_string(kReliabilityReliable) + "\n";
  yaml +=
      "  durability: " + std::to_string(latched ? kDurabilityTransientLocal : kDurabilityVolatile) +
      "\n";
  yaml += "  deadline" + zero_duration;
  yaml += "  lifespan" + zero_duration;
  yaml += "  liveliness: " + std::to_string(kLivelinessAutomatic) + "\n";
  yaml += "  liveliness_lease_duration" + zero_duration;
  yaml += "  avoid_ros_namespace_conventions: false";
  return yaml;
}

std::vector<std::pair<std::string, std::string>> channel_metadata(bool latched) {
  return {{"offered_qos_profiles", offered_qos_profiles(latched)}};
}

}  // namespace owsim::ros2
