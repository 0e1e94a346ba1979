#include "distributed/placed_frame_bytes.hpp"

#include "io/files/host_bytes.hpp"

namespace owsim {
namespace {

void put_pose(std::string& out, const Pose& pose) {
  put_host_bytes(out, pose.time_s);
  for (int i = 0; i < 3; ++i) put_host_bytes(out, pose.position_enu_m[i]);
  put_host_bytes(out, pose.attitude);
  for (int i = 0; i < 9; ++i) put_host_bytes(out, pose.frame_from_local_enu.data()[i]);
}

void get_pose(HostBytesReader& in, Pose& pose) {
  in.get(pose.time_s);
  for (int i = 0; i < 3; ++i) in.get(pose.position_enu_m[i]);
  in.get(pose.attitude);
  for (int i = 0; i < 9; ++i) in.get(pose.frame_from_local_enu.data()[i]);
}

}  // namespace

void append_placed_frame(const PlacedFrame& frame, std::string& out) {
  put_host_bytes(out, frame.frame);
  put_pose(out, frame.frame_start);
  put_host_bytes(out, frame.tally.pulses);
  put_host_bytes(out, frame.tally.returns_by_class);
  put_host_bytes(out, frame.tally.second_returns);
  put_host_vector(out, frame.tally.object_hits);
  put_host_bytes(out, frame.points);
  put_host_bytes(out, frame.csv_bytes);
  put_host_bytes(out, frame.las.points);
  put_host_bytes(out, frame.las.points_by_return);
  put_host_bytes(out, frame.las.min_record);
  put_host_bytes(out, frame.las.max_record);
  put_host_bytes(out, frame.truth_row_count);
  put_host_text(out, frame.truth_rows);
  put_host_text(out, frame.mcap_chunk);
}

std::vector<PlacedFrame> read_placed_frames(std::string_view bytes) {
  std::vector<PlacedFrame> frames;
  HostBytesReader in(bytes, "placed frames: the bytes end inside a frame");
  while (!in.empty()) {
    PlacedFrame& frame = frames.emplace_back();
    in.get(frame.frame);
    get_pose(in, frame.frame_start);
    in.get(frame.tally.pulses);
    in.get(frame.tally.returns_by_class);
    in.get(frame.tally.second_returns);
    in.get_vector(frame.tally.object_hits);
    in.get(frame.points);
    in.get(frame.csv_bytes);
    in.get(frame.las.points);
    in.get(frame.las.points_by_return);
    in.get(frame.las.min_record);
    in.get(frame.las.max_record);
    in.get(frame.truth_row_count);
    frame.truth_rows = in.get_text();
    frame.mcap_chunk = in.get_text();
  }
  return frames;
}

}  // namespace owsim
