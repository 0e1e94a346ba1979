// mcap_sample DIR: writes DIR/flight.mcap with every topic of flight.mcap (issue 47) — a few
// /owsim/points clouds, /tf, /tf_static, the /owsim/scene MarkerArray (a line strip, a cylinder,
// a triangle list, a cube) and /owsim/nav — over several chunks, and DIR/expected.json with every
// value written, for tests/mcap/read_mcap.mjs to compare with what the reference readers decode.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/mcap/cdr_writer.hpp"
#include "io/mcap/lidar_point_cloud.hpp"
#include "io/mcap/mcap_writer.hpp"
#include "io/mcap/ros2_messages.hpp"
#include "io/mcap/ros2_msg_definitions.hpp"
#include "io/mcap/ros2_qos.hpp"

namespace {

using Json = nlohmann::ordered_json;
using namespace owsim;
using namespace owsim::ros2;

constexpr int kFrames = 24;
constexpr int kPointsPerFrame = 1500;
constexpr std::int64_t kStartNs = 1'000'000'000'000;  // 1000 s on the trajectory's clock
constexpr std::int64_t kFramePeriodNs = 50'000'000;

Json to_json(const Time& time) { return {{"sec", time.sec}, {"nanosec", time.nanosec}}; }
Json to_json(const Header& header) {
  return {{"stamp", to_json(header.stamp)}, {"frame_id", header.frame_id}};
}
Json to_json(const Vector3& v) { return {{"x", v.x}, {"y", v.y}, {"z", v.z}}; }
Json to_json(const Quaternion& q) { return {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}}; }
Json to_json(const ColorRgba& c) { return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}}; }
Json bytes_json(const std::vector<unsigned char>& bytes) {
  Json array = Json::array();
  for (const unsigned char byte : bytes) array.push_back(byte);
  return array;
}
Json to_json(const TfMessage& message) {
  Json transforms = Json::array();
  for (const TransformStamped& t : message.transforms) {
    transforms.push_back({{"header", to_json(t.header)},
                          {"child_frame_id", t.child_frame_id},
                          {"transform",
                           {{"translation", to_json(t.transform.translation)},
                            {"rotation", to_json(t.transform.rotation)}}}});
  }
  return {{"transforms", transforms}};
}
Json to_json(const NavSatFix& fix) {
  return {{"header", to_json(fix.header)},
          {"status", {{"status", fix.status.status}, {"service", fix.status.service}}},
          {"latitude", fix.latitude},
          {"longitude", fix.longitude},
          {"altitude", fix.altitude},
          {"position_covariance", fix.position_covariance},
          {"position_covariance_type", fix.position_covariance_type}};
}
Json to_json(const MarkerArray& array) {
  Json markers = Json::array();
  for (const Marker& m : array.markers) {
    Json points = Json::array();
    for (const Point& p : m.points) points.push_back(to_json(p));
    Json colors = Json::array();
    for (const ColorRgba& c : m.colors) colors.push_back(to_json(c));
    Json uvs = Json::array();
    for (const UvCoordinate& uv : m.uv_coordinates) uvs.push_back({{"u", uv.u}, {"v", uv.v}});
    markers.push_back(
        {{"header", to_json(m.header)},
         {"ns", m.ns},
         {"id", m.id},
         {"type", m.type},
         {"action", m.action},
         {"pose",
          {{"position", to_json(m.pose.position)}, {"orientation", to_json(m.pose.orientation)}}},
         {"scale", to_json(m.scale)},
         {"color", to_json(m.color)},
         {"lifetime", to_json(m.lifetime)},
         {"frame_locked", m.frame_locked},
         {"points", points},
         {"colors", colors},
         {"texture_resource", m.texture_resource},
         {"texture",
          {{"header", to_json(m.texture.header)},
           {"format", m.texture.format},
           {"data", bytes_json(m.texture.data)}}},
         {"uv_coordinates", uvs},
         {"text", m.text},
         {"mesh_resource", m.mesh_resource},
         {"mesh_file",
          {{"filename", m.mesh_file.filename}, {"data", bytes_json(m.mesh_file.data)}}},
         {"mesh_use_embedded_materials", m.mesh_use_embedded_materials}});
  }
  return {{"markers", markers}};
}

MarkerArray scene(const Header& header) {
  MarkerArray scene;
  Marker wire;
  wire.header = header;
  wire.ns = wire.text = "span1_phase_a";
  wire.id = 0;
  wire.type = Marker::kLineStrip;
  wire.scale = {0.03, 0, 0};
  wire.color = {0.9f, 0.1f, 0.1f, 1};
  for (int i = 0; i <= 20; ++i) {
    const double x = 10.0 * i;
    wire.points.push_back({x, 50, 30 + 0.002 * (x - 100) * (x - 100)});
  }
  scene.markers.push_back(wire);
  Marker pole;
  pole.header = header;
  pole.ns = pole.text = "pole_7";
  pole.id = 1;
  pole.type = Marker::kCylinder;
  pole.pose.position = {0, 50, 17.5};
  pole.scale = {0.6, 0.6, 35};
  pole.color = {0.5f, 0.5f, 0.5f, 1};
  scene.markers.push_back(pole);
  Marker mesh;
  mesh.header = header;
  mesh.ns = mesh.text = "barn";
  mesh.id = 2;
  mesh.type = Marker::kTriangleList;
  mesh.points = {{0, 0, 0}, {10, 0, 0}, {10, 8, 0}, {0, 0, 0}, {10, 8, 0}, {0, 8, 6.25}};
  mesh.color = {0.6f, 0.4f, 0.2f, 1};
  mesh.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1},
                 {1, 1, 0, 1}, {0, 1, 1, 1}, {1, 0, 1, 1}};
  scene.markers.push_back(mesh);
  Marker fog;
  fog.header = header;
  fog.ns = fog.text = "fog_bank";
  fog.id = 3;
  fog.type = Marker::kCube;
  fog.pose.position = {150, -20, 40};
  fog.pose.orientation = {0, 0, std::sin(0.25), std::cos(0.25)};
  fog.scale = {120, 60, 80};
  fog.color = {0.8f, 0.8f, 0.85f, 0.3f};
  fog.lifetime = {0, 0};
  fog.frame_locked = true;
  fog.texture.format = "png";
  fog.texture.data = {0x89, 'P', 'N', 'G'};
  fog.uv_coordinates = {{0.25f, 0.75f}};
  fog.mesh_file.filename = "none.obj";
  fog.mesh_file.data = {1, 2, 3};
  scene.markers.push_back(fog);
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: mcap_sample DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  McapWriterOptions options;
  options.chunk_size = 256 * 1024;  // several chunks
  McapWriter writer(dir / "flight.mcap", options);
  Json expected;
  expected["topics"] = Json::object();
  Json& messages = expected["messages"] = Json::array();
  const auto add = [&](std::string_view topic, std::string_view type, bool latched) {
    const auto schema = writer.add_schema(type, kRos2MsgSchemaEncoding, ros2msg_schema(type));
    expected["topics"][std::string(topic)] = {{"type", type}, {"latched", latched}};
    return writer.add_channel(schema, topic, "cdr", channel_metadata(latched));
  };
  const auto points_channel = add("/owsim/points", kPointCloud2Type, false);
  const auto tf_channel = add("/tf", kTfMessageType, false);
  const auto tf_static_channel = add("/tf_static", kTfMessageType, true);
  const auto scene_channel = add("/owsim/scene", kMarkerArrayType, true);
  const auto nav_channel = add("/owsim/nav", kNavSatFixType, false);
  CdrWriter cdr;
  const auto write = [&](std::uint16_t channel, std::string_view topic, std::int64_t time_ns,
                         Json message) {
    writer.write_message(channel, static_cast<std::uint64_t>(time_ns), cdr.bytes());
    messages.push_back(
        {{"topic", topic}, {"log_time", std::to_string(time_ns)}, {"message", std::move(message)}});
  };

  const Header start{time_from_nanoseconds(kStartNs), "map"};
  TfMessage mount;
  mount.transforms.push_back({{start.stamp, "base_link"},
                              "owsim_sensor",
                              {{0.5, 0, -0.75}, {0, 0.0871557, 0, 0.9961947}}});
  cdr.clear();
  serialize(mount, cdr);
  write(tf_static_channel, "/tf_static", kStartNs, to_json(mount));
  const MarkerArray objects = scene(start);
  cdr.clear();
  serialize(objects, cdr);
  write(scene_channel, "/owsim/scene", kStartNs, to_json(objects));

  std::uint64_t state = 12345;
  const auto next = [&state] {  // a 64-bit LCG: the same values every run
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  std::vector<LidarPoint> points(kPointsPerFrame);
  std::vector<unsigned char> data;
  for (int frame = 0; frame < kFrames; ++frame) {
    const std::int64_t time_ns = kStartNs + frame * kFramePeriodNs;
    const Header header{time_from_nanoseconds(time_ns), "map"};
    Json rows = Json::array();
    for (LidarPoint& p : points) {
      p = {next() * 1000 - 500,
           next() * 1000,
           next() * 80,
           static_cast<float>(next()),
           static_cast<std::uint16_t>(1 + next() * 126),
           static_cast<std::uint8_t>(1 + next() * 3),
           static_cast<std::uint8_t>(next() * 19),
           time_ns * 1e-9 + next() * 0.05};
      rows.push_back(
          {p.x, p.y, p.z, p.intensity, p.ring, p.return_number, p.classification, p.time});
    }
    pack_lidar_points(points, data);
    const PointCloud2 cloud = lidar_point_cloud(header, data);
    cdr.clear();
    serialize(cloud, cdr);
    Json fields = Json::array();
    for (const PointField& f : cloud.fields) {
      fields.push_back(
          {{"name", f.name}, {"offset", f.offset}, {"datatype", f.datatype}, {"count", f.count}});
    }
    write(points_channel, "/owsim/points", time_ns,
          {{"header", to_json(header)},
           {"height", cloud.height},
           {"width", cloud.width},
           {"fields", fields},
           {"is_bigendian", cloud.is_bigendian},
           {"point_step", cloud.point_step},
           {"row_step", cloud.row_step},
           {"is_dense", cloud.is_dense},
           {"points", rows}});

    TfMessage pose;
    const double heading = 0.01 * frame;
    pose.transforms.push_back({header,
                               "base_link",
                               {{10.0 * frame, 2.5 * frame, 120 + 0.5 * frame},
                                {0, 0, std::sin(heading / 2), std::cos(heading / 2)}}});
    cdr.clear();
    serialize(pose, cdr);
    write(tf_channel, "/tf", time_ns, to_json(pose));

    NavSatFix fix;
    fix.header = {header.stamp, "owsim_sensor"};
    fix.status = {NavSatStatus::kStatusFix, NavSatStatus::kServiceGps};
    fix.latitude = 47.3769 + 1e-5 * frame;
    fix.longitude = 8.5417 + 2e-5 * frame;
    fix.altitude = 520.25 + frame;
    fix.position_covariance = {0.25, 0, 0, 0, 0.25, 0, 0, 0, 1};
    fix.position_covariance_type = NavSatFix::kCovarianceTypeDiagonalKnown;
    cdr.clear();
    serialize(fix, cdr);
    write(nav_channel, "/owsim/nav", time_ns, to_json(fix));
  }
  writer.finish();
  expected["chunks"] = writer.chunks_written();
  std::ofstream(dir / "expected.json") << expected.dump() << '\n';
  std::cout << "wrote " << (dir / "flight.mcap").string() << ": " << writer.messages_written()
            << " messages, " << writer.chunks_written() << " chunks, " << writer.bytes_written()
            << " bytes\n";
  return 0;
}
