// Protects the split of FlightOutputs::add_frame into a parallel encode_frame and a serial
// add_frame (io/run/frame_encoding.hpp): frames encoded out of order, on several threads, into a
// small pool of reused encodings, then added in order, give byte for byte the files of frames added
// one at a time, and the points and words of writers fed the old way (frame_points and the writers'
// write(), one point at a time); an encoding error surfaces when its frame is added, in frame
// order, and an encoding of another frame is refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "geometry/utm.hpp"
#include "io/points/frame_points.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/ply_writer.hpp"
#include "io/points/points_csv_writer.hpp"
#include "io/recording/frame_words.hpp"
#include "io/recording/word_file.hpp"
#include "io/run/flight_outputs.hpp"
#include "io/run/frame_encoding.hpp"
#include "sensor/scan_pattern.hpp"
#include "synthetic_flight.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

using test::content;
using test::files_under;
using test::small_scene;
using test::synthetic_frame;
using test::SyntheticFrame;

const Geodetic kOrigin{48.6881, 10.8447, 450.0};
constexpr std::int64_t kEncodedFrames = 9;
constexpr std::size_t kPool = 3;  // encodings in flight

class FrameEncodingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("owsim_frame_encoding_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    for (std::int64_t f = 0; f < kEncodedFrames; ++f) frames_.push_back(synthetic_frame(scan_, f));
  }
  void TearDown() override { fs::remove_all(dir_); }

  [[nodiscard]] FlightOutputOptions options(const std::string& folder) const {
    FlightOutputOptions o;
    o.directory = dir_ / folder;
    o.quicklook_every_nth_frame = 4;
    o.map_region = Eigen::AlignedBox2d(Eigen::Vector2d(-800.0, -800.0), Eigen::Vector2d(800, 800));
    return o;
  }

  // Every frame through add_frame(frame, frame_start), one at a time.
  void write_frame_by_frame(const std::string& folder) const {
    FlightOutputs outputs(options(folder), scene_, scan_, local_frame_);
    for (const SyntheticFrame& frame : frames_) outputs.add_frame(frame.view(), frame.start);
    outputs.finish({{"scenario", "synthetic"}});
  }

  // The frame's words and tally in blocks of whole lines, the last block first, as the frame
  // simulator's workers hand them over (the block sizes change from frame to frame, so a reused
  // encoding meets a different split), then the rest of the frame.
  void encode_in_blocks(const FlightOutputs& outputs, const SyntheticFrame& frame,
                        FrameEncoding& out) const {
    const int fibers = scan_.fibers_per_line;
    const int lines_per_block = 1 + static_cast<int>(frame.frame % 3) * 2;  // 1, 3, 5
    std::vector<std::pair<int, int>> blocks;
    for (int line = 0; line < scan_.lines_per_frame; line += lines_per_block) {
      const int end = std::min(scan_.lines_per_frame, line + lines_per_block);
      blocks.emplace_back(line * fibers, end * fibers);
    }
    for (auto block = blocks.rbegin(); block != blocks.rend(); ++block) {
      outputs.encode_pulses(frame_block(frame.view(), static_cast<std::size_t>(block->first),
                                        static_cast<std::size_t>(block->second)),
                            block->first, out);
    }
    outputs.finish_encoding(frame.view(), frame.start, out);
  }

  // The frames in batches of kPool, each batch encoded on kPool threads at once (the batch's last
  // frame first) into a pool of reused encodings, then added in order. Frames of odd index go
  // through encode_frame, the others block by block.
  void write_encoded_in_parallel(const std::string& folder) const {
    FlightOutputs outputs(options(folder), scene_, scan_, local_frame_);
    std::vector<FrameEncoding> pool(kPool);
    for (FrameEncoding& encoding : pool) outputs.size_encoding(encoding);
    for (std::size_t first = 0; first < frames_.size(); first += kPool) {
      const std::size_t end = std::min(first + kPool, frames_.size());
      std::vector<std::thread> workers;
      for (std::size_t f = end; f-- > first;) {
        workers.emplace_back([&, f] {
          if (f % 2 == 1) {
            outputs.encode_frame(frames_[f].view(), frames_[f].start, pool[f % kPool]);
          } else {
            encode_in_blocks(outputs, frames_[f], pool[f % kPool]);
          }
        });
      }
      for (std::thread& worker : workers) worker.join();
      for (std::size_t f = first; f < end; ++f)
        outputs.add_frame(frames_[f].view(), pool[f % kPool]);
    }
    outputs.finish({{"scenario", "synthetic"}});
  }

  // points.* and the word file the way FlightOutputs wrote them before the split: frame_points
  // and the writers' write(), here one point at a time.
  void write_old_way(const std::string& folder) const {
    const fs::path dir = dir_ / folder;
    fs::create_directories(dir);
    PointsCsvWriter csv(dir / "points.csv", {"span/1", "span/2", "p1", "t1", "terrain"});
    LasWriterOptions las_options;
    las_options.origin = kOrigin;
    LasWriter las(dir / "points.las", las_options);
    PlyWriter ply(dir / "points.ply");
    std::optional<MilowsWordWriter> milows;
    std::optional<HellasWordWriter> hellas;
    if (scan_.model == SensorModel::milows) {
      milows.emplace(dir / "flight.d64");
    } else {
      hellas.emplace(dir / "flight.hellas");
    }
    std::vector<PointRecord> points;
    const GeodesyCells geodesy(local_frame_, utm_grid_of(kOrigin));
    for (const SyntheticFrame& frame : frames_) {
      frame_points(frame.view(), geodesy, points, recorded_returns(scan_.model));
      for (const PointRecord& point : points) {
        csv.write({&point, 1});
        las.write({&point, 1});
        ply.write({&point, 1});
      }
      const auto n = frame.pulses.size();
      if (milows) {
        std::vector<std::uint64_t> words(n);
        pack_milows_frame(frame.pulses, frame.returns, words);
        milows->write(std::span<const std::uint64_t>(words));
      } else {
        if (frame.frame == 0) {
          hellas->write(hellas_file_header_word(frame.sweep, frame.pulses.front().time_s));
        }
        std::vector<std::uint32_t> words(n);
        pack_hellas_frame(scan_, frame.sweep, frame.pulses, frame.returns, words);
        hellas->write(std::span<const std::uint32_t>(words));
      }
    }
    csv.finish();
    las.finish();
    ply.finish();
    if (milows) milows->commit();
    if (hellas) hellas->commit();
  }

  void expect_same_bytes_every_way() const {
    write_frame_by_frame("one_by_one");
    write_encoded_in_parallel("parallel");
    write_old_way("old_way");
    const auto one_by_one = files_under(dir_ / "one_by_one");
    const auto parallel = files_under(dir_ / "parallel");
    const auto old_way = files_under(dir_ / "old_way");
    const std::string words = scan_.model == SensorModel::milows ? "flight.d64" : "flight.hellas";
    for (const std::string name :
         {words, std::string("points.csv"), std::string("points.las"), std::string("points.ply"),
          std::string("trajectory.csv"), std::string("summary.json"),
          std::string("quicklook/map.png"), std::string("quicklook/frame_000004.png")}) {
      ASSERT_TRUE(one_by_one.contains(name)) << name;
      ASSERT_TRUE(parallel.contains(name)) << name;
      EXPECT_TRUE(parallel.at(name) == one_by_one.at(name)) << name << " differs";
    }
    EXPECT_EQ(parallel.size(), one_by_one.size());
    for (const std::string name :
         {words, std::string("points.csv"), std::string("points.las"), std::string("points.ply")}) {
      ASSERT_TRUE(old_way.contains(name)) << name;
      EXPECT_TRUE(old_way.at(name) == one_by_one.at(name)) << name << " differs from the old way";
    }
    // Enough points that the comparison means something: about 0.45 returns a pulse.
    const auto rows =
        std::count(one_by_one.at("points.csv").begin(), one_by_one.at("points.csv").end(), '\n');
    EXPECT_GT(rows, static_cast<long>(kEncodedFrames) * scan_.pulses_per_frame() / 3);
  }

  fs::path dir_;
  ScanParams scan_;
  Scene scene_ = small_scene();
  LocalFrame local_frame_{kOrigin};
  std::vector<SyntheticFrame> frames_;
};

TEST_F(FrameEncodingTest, MilowsFramesEncodedInParallelGiveTheSameBytes) {
  expect_same_bytes_every_way();
}

TEST_F(FrameEncodingTest, HellasFramesEncodedInParallelGiveTheSameBytes) {
  scan_.model = SensorModel::hellas;
  frames_.clear();
  for (std::int64_t f = 0; f < kEncodedFrames; ++f) frames_.push_back(synthetic_frame(scan_, f));
  expect_same_bytes_every_way();
}

TEST_F(FrameEncodingTest, WithoutTheSummaryTheWordsAreTheSameAndNothingIsTallied) {
  write_frame_by_frame("all");
  FlightOutputOptions words_only = options("words_only");
  words_only.outputs = {OutputKind::d64};
  FlightOutputs outputs(words_only, scene_, scan_, local_frame_);
  std::vector<FrameEncoding> pool(2);
  for (FrameEncoding& encoding : pool) outputs.size_encoding(encoding);
  for (const SyntheticFrame& frame : frames_) {
    FrameEncoding& encoding = pool[static_cast<std::size_t>(frame.frame) % pool.size()];
    encode_in_blocks(outputs, frame, encoding);
    outputs.add_frame(frame.view(), encoding);
  }
  // The tally feeds summary.json alone, so a run without it skips it.
  EXPECT_EQ(outputs.summary().frames(), static_cast<std::uint64_t>(kEncodedFrames));
  EXPECT_EQ(outputs.summary().pulses(), 0u);
  EXPECT_EQ(outputs.summary().returns_of(SurfaceClass::ground), 0u);
  outputs.finish({});
  const auto all = files_under(dir_ / "all");
  const auto only = files_under(dir_ / "words_only");
  EXPECT_EQ(only.size(), 1u);
  ASSERT_TRUE(only.contains("flight.d64"));
  EXPECT_TRUE(only.at("flight.d64") == all.at("flight.d64"));
}

TEST_F(FrameEncodingTest, AnEncodingErrorSurfacesWhenItsFrameIsAdded) {
  // Frames 1 and 2 name objects the points.csv table does not hold; frame 2 is encoded first.
  frames_[1].returns[5].count = 1;
  frames_[1].returns[5].returns[0].object_index = 77;
  frames_[2].returns[5].count = 1;
  frames_[2].returns[5].returns[0].object_index = 99;
  FlightOutputs outputs(options("errors"), scene_, scan_, local_frame_);
  std::vector<FrameEncoding> pool(3);
  for (std::size_t f = 3; f-- > 0;)
    outputs.encode_frame(frames_[f].view(), frames_[f].start, pool[f]);
  EXPECT_FALSE(pool[0].error);
  EXPECT_TRUE(pool[2].error);
  outputs.add_frame(frames_[0].view(), pool[0]);
  try {
    outputs.add_frame(frames_[1].view(), pool[1]);
    FAIL() << "frame 1's error was not thrown";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("object index 77"), std::string::npos) << e.what();
  }
  EXPECT_EQ(outputs.frames_done(), 1);
}

TEST_F(FrameEncodingTest, PulsesThatAreNotWholeLinesOrAnUnsizedEncodingAreRefused) {
  FlightOutputs outputs(options("blocks"), scene_, scan_, local_frame_);
  const FrameView frame = frames_[0].view();
  const auto fibers = static_cast<std::size_t>(scan_.fibers_per_line);
  const auto pulses = static_cast<std::size_t>(scan_.pulses_per_frame());
  FrameEncoding unsized;
  EXPECT_THROW(outputs.encode_pulses(frame_block(frame, 0, fibers), 0, unsized), Error);
  FrameEncoding encoding;
  outputs.size_encoding(encoding);
  // (first pulse of the block's records, their end, the pulse they are said to start at)
  struct Case {
    std::size_t begin, end;
    int at;
  };
  for (const Case& c : std::vector<Case>{
           {1, fibers, 1},                                      // not from a line's start
           {0, fibers + 1, 0},                                  // not to a line's end
           {fibers, fibers, static_cast<int>(fibers)},          // no pulse
           {0, fibers, -static_cast<int>(fibers)},              // before the frame
           {0, 2 * fibers, static_cast<int>(pulses - fibers)},  // past its end
       }) {
    EXPECT_THROW(outputs.encode_pulses(frame_block(frame, c.begin, c.end), c.at, encoding), Error)
        << c.begin << ".." << c.end << " at " << c.at;
  }
  FrameView mismatched = frame_block(frame, fibers, 3 * fibers);
  mismatched.returns = mismatched.returns.first(fibers);
  EXPECT_THROW(outputs.encode_pulses(mismatched, static_cast<int>(fibers), encoding), Error);
  EXPECT_NO_THROW(outputs.encode_pulses(frame_block(frame, fibers, 3 * fibers),
                                        static_cast<int>(fibers), encoding));
}

TEST_F(FrameEncodingTest, AnEncodingOfAnotherFrameIsRefused) {
  FlightOutputs outputs(options("mismatch"), scene_, scan_, local_frame_);
  FrameEncoding encoding;
  outputs.encode_frame(frames_[1].view(), frames_[1].start, encoding);
  try {
    outputs.add_frame(frames_[0].view(), encoding);
    FAIL() << "an encoding of frame 1 was taken for frame 0";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("encoding of frame 1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(outputs.frames_done(), 0);
}

}  // namespace
}  // namespace owsim
