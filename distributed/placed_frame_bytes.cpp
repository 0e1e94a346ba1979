#include "distributed/placed_frame_bytes.hpp"

#include <cstring>
#include <type_traits>

#include "geometry/error.hpp"

namespace owsim {
namespace {

template <typename T>
void put(std::string& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (bytes_.size() < sizeof value) throw Error("placed frames: the bytes end inside a frame");
    std::memcpy(&value, bytes_.data(), sizeof value);
    bytes_.remove_prefix(sizeof value);
  }
  [[nodiscard]] std::string get_text(std::uint64_t size) {
    if (bytes_.size() < size) throw Error("placed frames: the bytes end inside a frame");
    std::string text(bytes_.substr(0, static_cast<std::size_t>(size)));
    bytes_.remove_prefix(static_cast<std::size_t>(size));
    return text;
  }
  [[nodiscard]] bool empty() const { return bytes_.empty(); }

 private:
  std::string_view bytes_;
};

void put_pose(std::string& out, const Pose& pose) {
  put(out, pose.time_s);
  for (int i = 0; i < 3; ++i) put(out, pose.position_enu_m[i]);
  put(out, pose.attitude);
  for (int i = 0; i < 9; ++i) put(out, pose.frame_from_local_enu.data()[i]);
}

void get_pose(Reader& in, Pose& pose) {
  in.get(pose.time_s);
  for (int i = 0; i < 3; ++i) in.get(pose.position_enu_m[i]);
  in.get(pose.attitude);
  for (int i = 0; i < 9; ++i) in.get(pose.frame_from_local_enu.data()[i]);
}

}  // namespace

void append_placed_frame(const PlacedFrame& frame, std::string& out) {
  put(out, frame.frame);
  put_pose(out, frame.frame_start);
  put(out, frame.tally.pulses);
  put(out, frame.tally.returns_by_class);
  put(out, frame.tally.second_returns);
  put(out, static_cast<std::uint64_t>(frame.tally.object_hits.size()));
  for (const FrameTally::ObjectHit& hit : frame.tally.object_hits) put(out, hit);
  put(out, frame.points);
  put(out, frame.csv_bytes);
  put(out, frame.las.points);
  put(out, frame.las.points_by_return);
  put(out, frame.las.min_record);
  put(out, frame.las.max_record);
  put(out, frame.truth_row_count);
  put(out, static_cast<std::uint64_t>(frame.truth_rows.size()));
  out += frame.truth_rows;
  put(out, static_cast<std::uint64_t>(frame.mcap_chunk.size()));
  out += frame.mcap_chunk;
}

std::vector<PlacedFrame> read_placed_frames(std::string_view bytes) {
  std::vector<PlacedFrame> frames;
  Reader in(bytes);
  while (!in.empty()) {
    PlacedFrame& frame = frames.emplace_back();
    in.get(frame.frame);
    get_pose(in, frame.frame_start);
    in.get(frame.tally.pulses);
    in.get(frame.tally.returns_by_class);
    in.get(frame.tally.second_returns);
    std::uint64_t hits = 0;
    in.get(hits);
    if (hits > bytes.size()) throw Error("placed frames: the bytes end inside a frame");
    frame.tally.object_hits.resize(hits);
    for (FrameTally::ObjectHit& hit : frame.tally.object_hits) in.get(hit);
    in.get(frame.points);
    in.get(frame.csv_bytes);
    in.get(frame.las.points);
    in.get(frame.las.points_by_return);
    in.get(frame.las.min_record);
    in.get(frame.las.max_record);
    in.get(frame.truth_row_count);
    std::uint64_t truth_bytes = 0;
    in.get(truth_bytes);
    frame.truth_rows = in.get_text(truth_bytes);
    std::uint64_t mcap_bytes = 0;
    in.get(mcap_bytes);
    frame.mcap_chunk = in.get_text(mcap_bytes);
  }
  return frames;
}

}  // namespace owsim
