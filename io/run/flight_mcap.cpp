#include "io/run/flight_mcap.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "geometry/error.hpp"
#include "geometry/rotation.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/mcap/ros2_msg_definitions.hpp"
#include "io/mcap/ros2_qos.hpp"
#include "io/mcap/scene_markers.hpp"
#include "io/points/las_writer.hpp"

namespace owsim {
namespace {

constexpr std::int64_t kNanosecondsPerSecond = 1'000'000'000;

// The channels, in the order they are added (their ids), with their schemas' types.
struct Topic {
  std::string_view name;
  std::string_view type;
  bool latched;
};
constexpr Topic kTopics[] = {
    {"/owsim/points", ros2::kPointCloud2Type, false}, {"/tf", ros2::kTfMessageType, false},
    {"/owsim/nav", ros2::kNavSatFixType, false},      {"/tf_static", ros2::kTfMessageType, true},
    {"/owsim/scene", ros2::kMarkerArrayType, true},
};
constexpr std::uint16_t kPointsChannel = 1, kTfChannel = 2, kNavChannel = 3, kTfStaticChannel = 4,
                        kSceneChannel = 5;

// The trajectory's body axes (x forward, y right, z down) from REP-103's (x forward, y left, z up)
// and back: a half turn about x.
const Eigen::Matrix3d& body_from_rep103() {
  static const Eigen::Matrix3d turn = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return turn;
}

ros2::Quaternion quaternion(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // one of the two: w ≥ 0
  return {q.x(), q.y(), q.z(), q.w()};
}

ros2::Vector3 vector(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// A YAML double-quoted scalar.
std::string yaml_quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '\n') {
      out += "\\n";
    } else {
      if (c == '"' || c == '\\') out += '\\';
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

FlightMcapClock::FlightMcapClock(const ScanParams& scan)
    : offset_s_(scan.start_s < 0 ? static_cast<std::int64_t>(std::ceil(-scan.start_s)) : 0) {}

std::uint64_t FlightMcapClock::nanoseconds(double time_s) const {
  const double shifted = time_s + static_cast<double>(offset_s_);
  if (!(shifted >= 0) || shifted > static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    throw Error("flight.mcap: time " + std::to_string(time_s) +
                " s is outside what a ROS 2 stamp holds (0 to 2^31 s after the shift of " +
                std::to_string(offset_s_) + " s)");
  }
  return static_cast<std::uint64_t>(std::llround(time_s * 1e9) + offset_s_ * kNanosecondsPerSecond);
}

ros2::Time FlightMcapClock::stamp(std::uint64_t nanoseconds) {
  return ros2::time_from_nanoseconds(static_cast<std::int64_t>(nanoseconds));
}

ros2::TransformStamped map_to_base_link(const Pose& pose, const ros2::Time& stamp) {
  ros2::TransformStamped transform;
  transform.header.stamp = stamp;
  transform.header.frame_id = "map";
  transform.child_frame_id = "base_link";
  transform.transform.translation = vector(pose.position_enu_m);
  transform.transform.rotation = quaternion(pose.frame_from_local_enu * enu_from_ned_matrix() *
                                            body_to_ned(pose.attitude) * body_from_rep103());
  return transform;
}

ros2::TransformStamped base_link_to_sensor(const Mount& mount, const ros2::Time& stamp) {
  // The sensor's own axes (x boresight, y right, z down: β right, α up, sensor/mounting.hpp) are
  // turned into base_link's by the mount; both sides in REP-103's axes.
  const Eigen::Matrix3d& turn = body_from_rep103();
  ros2::TransformStamped transform;
  transform.header.stamp = stamp;
  transform.header.frame_id = "base_link";
  transform.child_frame_id = "owsim_sensor";
  transform.transform.translation = vector(turn * mount.lever_arm_m);
  transform.transform.rotation = quaternion(turn * mount_rotation(mount) * turn);
  return transform;
}

FlightMcapEncoder::FlightMcapEncoder(const ScanParams& scan, const LocalFrame& local_frame)
    : clock_(scan), local_frame_(&local_frame) {}

void FlightMcapEncoder::encode(std::int64_t frame, const Pose& frame_start,
                               std::span<const PointRecord> points, McapFrameEncoding& out) const {
  const std::uint64_t time_ns = clock_.nanoseconds(frame_start.time_s);
  const ros2::Time stamp = FlightMcapClock::stamp(time_ns);
  const auto sequence = static_cast<std::uint32_t>(frame);
  out.chunk.clear();

  out.points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PointRecord& record = points[i];
    ros2::LidarPoint& point = out.points[i];
    point.x = record.enu_m.x();
    point.y = record.enu_m.y();
    point.z = record.enu_m.z();
    point.intensity = static_cast<float>(record.energy_rel);
    point.ring = static_cast<std::uint16_t>(record.fiber);
    point.return_number = static_cast<std::uint8_t>(record.return_number);
    point.classification = las_classification(record.surface);
    point.time = record.time_s;
  }
  ros2::pack_lidar_points(out.points, out.packed_points);
  out.message.clear();
  ros2::serialize(ros2::lidar_point_cloud({stamp, "map"}, out.packed_points), out.message);
  out.chunk.add_message(kPointsChannel, sequence, time_ns, time_ns, out.message.bytes());

  out.message.clear();
  ros2::serialize(ros2::TfMessage{{map_to_base_link(frame_start, stamp)}}, out.message);
  out.chunk.add_message(kTfChannel, sequence, time_ns, time_ns, out.message.bytes());

  ros2::NavSatFix fix;
  fix.header = {stamp, "base_link"};
  fix.status = {ros2::NavSatStatus::kStatusFix, ros2::NavSatStatus::kServiceGps};
  const Geodetic position = local_frame_->geodetic_from_enu(frame_start.position_enu_m);
  fix.latitude = position.lat_deg;
  fix.longitude = position.lon_deg;
  fix.altitude = position.h_m;
  out.message.clear();
  ros2::serialize(fix, out.message);
  out.chunk.add_message(kNavChannel, sequence, time_ns, time_ns, out.message.bytes());
  out.chunk.finish();
}

FlightMcapFile::FlightMcapFile(const std::filesystem::path& directory, const Scene& scene,
                               const ScanParams& scan, const Mount& mount)
    : directory_(directory),
      writer_(directory / "flight.mcap"),
      start_ns_(FlightMcapClock(scan).nanoseconds(scan.start_s)),
      end_ns_(start_ns_),
      topic_messages_(std::size(kTopics), 0) {
  std::vector<std::pair<std::string_view, std::uint16_t>> schemas;
  for (const Topic& topic : kTopics) {
    const auto known = std::find_if(schemas.begin(), schemas.end(),
                                    [&](const auto& schema) { return schema.first == topic.type; });
    std::uint16_t schema = 0;
    if (known != schemas.end()) {
      schema = known->second;
    } else {
      schema = writer_.add_schema(topic.type, ros2::kRos2MsgSchemaEncoding,
                                  ros2::ros2msg_schema(topic.type));
      schemas.emplace_back(topic.type, schema);
    }
    writer_.add_channel(schema, topic.name, "cdr", ros2::channel_metadata(topic.latched));
  }
  const ros2::Time stamp = FlightMcapClock::stamp(start_ns_);
  CdrWriter message;
  ros2::serialize(ros2::TfMessage{{base_link_to_sensor(mount, stamp)}}, message);
  writer_.write_message(kTfStaticChannel, start_ns_, message.bytes());
  message.clear();
  ros2::serialize(ros2::scene_markers(scene, stamp), message);
  writer_.write_message(kSceneChannel, start_ns_, message.bytes());
  writer_.close_chunk();
  topic_messages_[kTfStaticChannel - 1] = topic_messages_[kSceneChannel - 1] = 1;
}

void FlightMcapFile::append(const McapChunk& frame) {
  writer_.write_chunk(frame);
  for (const McapChunk::ChannelMessages& channel : frame.channels()) {
    topic_messages_[channel.channel_id - 1] += channel.count;
  }
  if (frame.has_messages()) end_ns_ = std::max(end_ns_, frame.end_time());
}

void FlightMcapFile::finish() {
  writer_.finish();
  const std::string start = std::to_string(start_ns_);
  const std::string duration = std::to_string(end_ns_ - start_ns_);
  const std::string messages = std::to_string(writer_.messages_written());
  std::string yaml = "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n";
  yaml += "  duration:\n    nanoseconds: " + duration + "\n";
  yaml += "  starting_time:\n    nanoseconds_since_epoch: " + start + "\n";
  yaml += "  message_count: " + messages + "\n";
  yaml += "  topics_with_message_count:\n";
  for (std::size_t i = 0; i < std::size(kTopics); ++i) {
    const Topic& topic = kTopics[i];
    yaml += "    - topic_metadata:\n";
    yaml += "        name: " + std::string(topic.name) + "\n";
    yaml += "        type: " + std::string(topic.type) + "\n";
    yaml += "        serialization_format: cdr\n";
    yaml +=
        "        offered_qos_profiles: " + yaml_quoted(ros2::offered_qos_profiles(topic.latched)) +
        "\n";
    yaml += "      message_count: " + std::to_string(topic_messages_[i]) + "\n";
  }
  yaml += "  compression_format: \"\"\n  compression_mode: \"\"\n";
  yaml += "  relative_file_paths:\n    - flight.mcap\n";
  yaml += "  files:\n    - path: flight.mcap\n";
  yaml += "      starting_time:\n        nanoseconds_since_epoch: " + start + "\n";
  yaml += "      duration:\n        nanoseconds: " + duration + "\n";
  yaml += "      message_count: " + messages + "\n";
  AtomicOutputFile metadata(directory_ / "metadata.yaml");
  metadata.write(yaml);
  metadata.commit();
}

}  // namespace owsim
