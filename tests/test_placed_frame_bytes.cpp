// The frames a distributed run gathers at process 0 (distributed/placed_frame_bytes.hpp) come back
// field for field, however many and whatever they hold; bytes cut short are refused.
#include <gtest/gtest.h>

#include <random>

#include "distributed/placed_frame_bytes.hpp"
#include "geometry/error.hpp"

namespace owsim {
namespace {

PlacedFrame random_frame(std::mt19937_64& random, std::int64_t frame) {
  std::uniform_real_distribution<double> real(-1e4, 1e4);
  std::uniform_int_distribution<std::uint64_t> count(0, 1u << 20);
  PlacedFrame placed;
  placed.frame = frame;
  placed.frame_start.time_s = real(random);
  placed.frame_start.position_enu_m = {real(random), real(random), real(random)};
  placed.frame_start.attitude = {real(random), real(random), real(random)};
  for (int i = 0; i < 9; ++i) placed.frame_start.frame_from_local_enu.data()[i] = real(random);
  placed.tally.pulses = count(random);
  for (auto& c : placed.tally.returns_by_class) c = count(random);
  placed.tally.second_returns = count(random);
  const auto hits = static_cast<std::size_t>(count(random) % 50);
  for (std::size_t h = 0; h < hits; ++h) {
    placed.tally.object_hits.push_back({static_cast<std::uint32_t>(count(random)),
                                        static_cast<std::uint32_t>(count(random) % 2), real(random),
                                        real(random)});
  }
  placed.points = count(random);
  placed.csv_bytes = count(random);
  placed.las.points = count(random);
  for (auto& c : placed.las.points_by_return) c = count(random);
  for (int axis = 0; axis < 3; ++axis) {
    placed.las.min_record[axis] = static_cast<std::int32_t>(real(random));
    placed.las.max_record[axis] = static_cast<std::int32_t>(real(random));
  }
  placed.mcap_chunk.resize(static_cast<std::size_t>(count(random) % 300));
  for (char& c : placed.mcap_chunk) c = static_cast<char>(count(random));
  return placed;
}

void expect_same(const PlacedFrame& a, const PlacedFrame& b) {
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.frame_start.time_s, b.frame_start.time_s);
  EXPECT_EQ(a.frame_start.position_enu_m, b.frame_start.position_enu_m);
  EXPECT_EQ(a.frame_start.attitude.roll_deg, b.frame_start.attitude.roll_deg);
  EXPECT_EQ(a.frame_start.attitude.heading_deg, b.frame_start.attitude.heading_deg);
  EXPECT_EQ(a.frame_start.frame_from_local_enu, b.frame_start.frame_from_local_enu);
  EXPECT_EQ(a.tally.pulses, b.tally.pulses);
  EXPECT_EQ(a.tally.returns_by_class, b.tally.returns_by_class);
  EXPECT_EQ(a.tally.second_returns, b.tally.second_returns);
  ASSERT_EQ(a.tally.object_hits.size(), b.tally.object_hits.size());
  for (std::size_t h = 0; h < a.tally.object_hits.size(); ++h) {
    EXPECT_EQ(a.tally.object_hits[h].object, b.tally.object_hits[h].object);
    EXPECT_EQ(a.tally.object_hits[h].time_s, b.tally.object_hits[h].time_s);
    EXPECT_EQ(a.tally.object_hits[h].true_range_m, b.tally.object_hits[h].true_range_m);
  }
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.csv_bytes, b.csv_bytes);
  EXPECT_EQ(a.las.points, b.las.points);
  EXPECT_EQ(a.las.points_by_return, b.las.points_by_return);
  EXPECT_EQ(a.las.min_record, b.las.min_record);
  EXPECT_EQ(a.las.max_record, b.las.max_record);
  EXPECT_EQ(a.mcap_chunk, b.mcap_chunk);
}

TEST(PlacedFrameBytes, FramesComeBackFieldForField) {
  std::mt19937_64 random(18);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<PlacedFrame> frames;
    std::string bytes;
    for (int f = 0; f < trial; ++f) {
      frames.push_back(random_frame(random, 100 + f));
      append_placed_frame(frames.back(), bytes);
    }
    const std::vector<PlacedFrame> back = read_placed_frames(bytes);
    ASSERT_EQ(back.size(), frames.size());
    for (std::size_t f = 0; f < frames.size(); ++f) expect_same(frames[f], back[f]);
  }
}

TEST(PlacedFrameBytes, BytesCutShortAreRefused) {
  std::mt19937_64 random(7);
  std::string bytes;
  append_placed_frame(random_frame(random, 0), bytes);
  for (const std::size_t cut : {std::size_t{1}, std::size_t{8}, bytes.size() / 2}) {
    EXPECT_THROW(static_cast<void>(read_placed_frames(bytes.substr(0, bytes.size() - cut))), Error);
  }
  EXPECT_TRUE(read_placed_frames("").empty());
}

}  // namespace
}  // namespace owsim
