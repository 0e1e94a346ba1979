// Protects the checkpoint of `owsim run` (io/run/run_checkpoint.hpp) and FlightOutputs' resume:
// every accumulated value survives the checkpoint file exactly (doubles, optionals, the LAS
// statistics, the quick-look map mask); a damaged file or another run's checkpoint is a one-line
// error naming it; and outputs killed mid-flight (a child process that exits without running a
// destructor) then resumed from the checkpoint — also when the kill came while finish() was
// committing — end byte for byte as uninterrupted outputs written without checkpoints: words
// (MilOWS and HELLAS), points, trajectory, quick-look images and map, summary.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/binary_record.hpp"
#include "io/run/flight_outputs.hpp"
#include "io/run/run_checkpoint.hpp"
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

class RunCheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("owsim_run_checkpoint_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

// Names of the files that differ (or exist on one side only).
std::vector<std::string> differing(const std::map<std::string, std::string>& a,
                                   const std::map<std::string, std::string>& b) {
  std::vector<std::string> names;
  for (const auto& [name, bytes] : a) {
    if (!b.contains(name) || b.at(name) != bytes) names.push_back(name);
  }
  for (const auto& [name, bytes] : b) {
    if (!a.contains(name)) names.push_back(name);
  }
  return names;
}

// ---- the checkpoint file ----

RunCheckpoint every_field_set() {
  RunCheckpoint c;
  c.run = {{"seed", 2024}, {"scenario_file", "0123456789abcdef"}, {"no_noise", false}};
  c.frames_done = 7;
  c.finishing = true;
  c.summary.counts = {7, 142'464, {11, 22, 33, 44, 55, 66}, 5};
  ObjectTruth seen;
  seen.returns = 12;
  seen.frames_seen = 3;
  seen.first_seen_s = 0.1 + 0.2;  // 0.30000000000000004: needs all 17 digits
  seen.first_seen_range_m = 1.0 / 3.0;
  seen.min_range_m = std::numeric_limits<double>::denorm_min();
  seen.last_frame_seen = 6;
  seen.seen_through_fog = 4;
  seen.first_seen_clear_s = 2.0 / 3.0;
  seen.first_seen_clear_range_m = 1e-300;
  ObjectTruth later = seen;
  later.returns = std::numeric_limits<std::uint64_t>::max();
  later.first_seen_s = -0.0;
  later.last_frame_seen = std::numeric_limits<std::int64_t>::max();
  c.summary.object_count = 1'000'000;  // seen in this order: 999999 first, then 3
  c.summary.seen = {{999'999, later}, {3, seen}};
  c.words = WriterCheckpoint{8 * 142'464, 142'464};
  c.points_csv = WriterCheckpoint{123'456'789'012, 987'654};
  LasCheckpoint las;
  las.file = {375 + 54 + 700 + 30 * 4, 4};
  las.points_by_return = {3, 1};
  las.min_record = {std::numeric_limits<std::int32_t>::min(), -5, 0};
  las.max_record = {std::numeric_limits<std::int32_t>::max(), 17, 123'456};
  las.creation_date = {366, 2024};
  c.points_las = las;
  c.points_ply = WriterCheckpoint{400 + 29 * 4, 4};
  c.trajectory = WriterCheckpoint{500, 7};
  QuicklookCheckpoint quicklook;
  // Runs of every length class of the run-length code (1, 127, 128, 16383, 16384, ~1 M) and a
  // stretch of noise.
  std::mt19937_64 rng(3);
  for (const std::size_t run : {1u, 127u, 128u, 16'383u, 16'384u, 1'000'000u}) {
    quicklook.map_mask.insert(quicklook.map_mask.end(), run, static_cast<std::uint8_t>(run % 251));
  }
  for (int i = 0; i < 5000; ++i) quicklook.map_mask.push_back(static_cast<std::uint8_t>(rng()));
  quicklook.last_trajectory_px = Eigen::Vector2d(1023.4999999999999, -0.5);
  c.quicklook = quicklook;
  return c;
}

TEST_F(RunCheckpointTest, EveryValueRoundTripsExactly) {
  const RunCheckpoint written = every_field_set();
  const fs::path path = run_checkpoint_path(dir_);
  EXPECT_EQ(path, dir_ / ".owsim-resume");
  write_run_checkpoint(path, written);
  EXPECT_FALSE(fs::exists(AtomicOutputFile::partial_path_for(path)));
  const std::optional<RunCheckpoint> read = read_run_checkpoint(path);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->run, written.run);
  EXPECT_EQ(read->summary, written.summary);
  EXPECT_EQ(read->points_las, written.points_las);
  EXPECT_EQ(read->quicklook, written.quicklook);
  EXPECT_TRUE(*read == written);
}

TEST_F(RunCheckpointTest, AbsentOutputsStayAbsent) {
  RunCheckpoint written;
  written.frames_done = 0;
  written.words = WriterCheckpoint{0, 0};
  const fs::path path = run_checkpoint_path(dir_);
  write_run_checkpoint(path, written);
  const std::optional<RunCheckpoint> read = read_run_checkpoint(path);
  ASSERT_TRUE(read.has_value());
  EXPECT_TRUE(read->words.has_value());
  EXPECT_FALSE(read->points_csv || read->points_las || read->points_ply || read->trajectory ||
               read->quicklook);
  EXPECT_TRUE(*read == written);
}

TEST_F(RunCheckpointTest, NoFileIsNoCheckpoint) {
  EXPECT_FALSE(read_run_checkpoint(run_checkpoint_path(dir_)).has_value());
}

TEST_F(RunCheckpointTest, DamagedFileIsAOneLineErrorNamingIt) {
  const fs::path path = run_checkpoint_path(dir_);
  write_run_checkpoint(path, every_field_set());
  const std::string whole = content(path);
  const auto message_for = [&](const std::string& text) -> std::string {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    try {
      (void)read_run_checkpoint(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  // Cut short; one byte changed (the checksum refuses it); behind a correct checksum: more seen
  // objects than the file holds, a body cut inside the map's runs, a byte after the last state;
  // another format version; the JSON checkpoint of an earlier owsim.
  const std::string body = whole.substr(20);
  std::string flipped = whole;
  flipped[whole.size() / 2] ^= 0x10;
  BinaryRecordWriter run;
  run.put_bytes("{}");
  BinaryRecordWriter counts;
  for (int i = 0; i < 9; ++i) counts.put(std::uint64_t{0});
  counts.put(std::uint64_t{1} << 40);  // seen objects
  std::string too_many = run.bytes();
  too_many += std::string(8 + 1, '\0');  // frames done, finishing
  too_many += counts.bytes();
  std::string old_version = whole;
  old_version[8] = 2;
  for (const std::string& text :
       {whole.substr(0, whole.size() / 2), flipped, checkpoint_file_bytes(too_many),
        checkpoint_file_bytes(body.substr(0, body.size() - 20)), checkpoint_file_bytes(body + "x"),
        old_version,
        std::string("owsim run checkpoint fnv1a64 0123456789abcdef\n{\"format\": \"x\"}")}) {
    const std::string message = message_for(text);
    EXPECT_EQ(message.rfind(path.string() + ": damaged checkpoint", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_F(RunCheckpointTest, AnotherRunIsNamedByTheFirstKeyThatDiffers) {
  const fs::path path = run_checkpoint_path(dir_);
  const nlohmann::json run = {{"frames", 120}, {"seed", 2024}, {"outputs", "d64"}};
  EXPECT_NO_THROW(require_same_run(path, run, run));
  nlohmann::json other = run;
  other["seed"] = 7;
  try {
    require_same_run(path, run, other);
    FAIL() << "another seed was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              path.string() +
                  ": written by a different run: seed was 2024, now 7 (run without --resume to "
                  "start over)");
  }
  nlohmann::json fewer = run;
  fewer.erase("outputs");
  EXPECT_THROW(require_same_run(path, run, fewer), Error);
  EXPECT_THROW(require_same_run(path, fewer, run), Error);
}

TEST_F(RunCheckpointTest, ContentHashIsFnv1a64) {
  // Reference values of the FNV-1a 64-bit hash (Fowler, Noll, Vo test suite).
  const auto hash_of = [](const std::string& text) {
    ContentHash hash;
    hash.add(text.data(), text.size());
    return hash.hex();
  };
  EXPECT_EQ(hash_of(""), "cbf29ce484222325");
  EXPECT_EQ(hash_of("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(hash_of("foobar"), "85944171f73967e8");
  const std::string bytes(200'000, 'x');
  std::ofstream(dir_ / "file", std::ios::binary) << bytes;
  ContentHash file;
  file.add_file(dir_ / "file");
  EXPECT_EQ(file.hex(), hash_of(bytes));
  EXPECT_THROW(file.add_file(dir_ / "missing"), Error);
}

// ---- FlightOutputs killed and resumed ----

constexpr std::int64_t kFrames = 12;

class FlightOutputsResume : public RunCheckpointTest {
 protected:
  [[nodiscard]] FlightOutputOptions options(const std::string& folder, bool checkpoints) const {
    FlightOutputOptions o;
    o.directory = dir_ / folder;
    o.quicklook_every_nth_frame = 5;
    o.map_region = Eigen::AlignedBox2d(Eigen::Vector2d(-800.0, -800.0), Eigen::Vector2d(800, 800));
    if (checkpoints) o.checkpoint_run = {{"test", "resume"}};
    o.checkpoint_interval_s = 0.0;  // after every frame
    o.outputs = outputs_;
    return o;
  }

  // Frames [first, end) into `outputs`.
  void add_frames(FlightOutputs& outputs, std::int64_t first, std::int64_t end) const {
    for (std::int64_t f = first; f < end; ++f) {
      const SyntheticFrame frame = synthetic_frame(scan_, f);
      outputs.add_frame(frame.view(), frame.start);
    }
  }

  // The uninterrupted outputs, without checkpoints, in reference/.
  void write_reference() const {
    FlightOutputs outputs(options("reference", false), scene_, scan_, local_frame_);
    add_frames(outputs, 0, kFrames);
    outputs.finish({{"scenario", "synthetic"}});
  }

  // Frames [0, frames) into interrupted/ by a child process that then dies without running a
  // destructor, as under SIGKILL; bytes it wrote after its last checkpoint are added to each
  // temporary.
  void kill_after(std::int64_t frames) const {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        auto* outputs =
            new FlightOutputs(options("interrupted", true), scene_, scan_, local_frame_);
        add_frames(*outputs, 0, frames);
      } catch (...) {
        ::_exit(1);
      }
      ::_exit(0);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    for (const auto& entry : fs::directory_iterator(dir_ / "interrupted")) {
      if (entry.path().extension() == ".partial") {
        std::ofstream(entry.path(), std::ios::binary | std::ios::app) << "after the checkpoint";
      }
    }
  }

  // Resumes interrupted/ from its checkpoint and finishes it.
  void resume(std::int64_t expected_frames_done) const {
    const std::optional<RunCheckpoint> checkpoint =
        read_run_checkpoint(run_checkpoint_path(dir_ / "interrupted"));
    ASSERT_TRUE(checkpoint.has_value());
    FlightOutputs outputs(options("interrupted", true), scene_, scan_, local_frame_, &*checkpoint);
    EXPECT_EQ(outputs.frames_done(), expected_frames_done);
    add_frames(outputs, outputs.frames_done(), kFrames);
    EXPECT_EQ(outputs.summary().frames(), static_cast<std::uint64_t>(kFrames));
    outputs.finish({{"scenario", "synthetic"}});
  }

  void expect_same_outputs() const {
    const auto reference = files_under(dir_ / "reference");
    EXPECT_TRUE(reference.contains("flight.d64") || reference.contains("flight.hellas"));
    EXPECT_TRUE(reference.contains("quicklook/map.png"));
    EXPECT_TRUE(reference.contains("quicklook/frame_000010.png"));
    const std::size_t point_files = outputs_.count(OutputKind::csv) +
                                    outputs_.count(OutputKind::las) +
                                    outputs_.count(OutputKind::ply);
    EXPECT_EQ(reference.size(), 7u + point_files);  // words, trajectory, summary, 3 + 1 PNGs
    const std::vector<std::string> names = differing(reference, files_under(dir_ / "interrupted"));
    EXPECT_TRUE(names.empty()) << "differ: " << testing::PrintToString(names);
  }

  std::set<OutputKind> outputs_ = all_outputs();
  ScanParams scan_;
  Scene scene_ = small_scene();
  LocalFrame local_frame_{kOrigin};
};

TEST_F(FlightOutputsResume, KilledMidFlightResumesToTheUninterruptedBytes) {
  write_reference();
  kill_after(7);
  EXPECT_FALSE(fs::exists(dir_ / "interrupted" / "flight.d64"));
  EXPECT_TRUE(fs::exists(dir_ / "interrupted" / "flight.d64.partial"));
  resume(7);
  EXPECT_FALSE(fs::exists(run_checkpoint_path(dir_ / "interrupted")));
  expect_same_outputs();
}

// A run without points.csv and points.ply resumes: the checkpoint holds no state for the
// outputs it was not asked for, and none is looked for (mpi_run.sh found this).
TEST_F(FlightOutputsResume, OutputsNotAskedForAreNotLookedForInTheCheckpoint) {
  outputs_.erase(OutputKind::csv);
  outputs_.erase(OutputKind::ply);
  write_reference();
  kill_after(5);
  resume(5);
  expect_same_outputs();
}

TEST_F(FlightOutputsResume, HellasWordsResumeWithoutASecondHeaderWord) {
  scan_.model = SensorModel::hellas;
  write_reference();
  kill_after(4);
  resume(4);
  expect_same_outputs();
}

TEST_F(FlightOutputsResume, KilledWhileFinishingKeepsWhatWasCommitted) {
  write_reference();
  kill_after(kFrames);
  // finish() had written its checkpoint and committed the words and points.csv when it died.
  const fs::path path = run_checkpoint_path(dir_ / "interrupted");
  RunCheckpoint checkpoint = *read_run_checkpoint(path);
  ASSERT_EQ(checkpoint.frames_done, kFrames);
  checkpoint.finishing = true;
  write_run_checkpoint(path, checkpoint);
  for (const std::string name : {"flight.d64", "points.csv"}) {
    const fs::path final_path = dir_ / "interrupted" / name;
    fs::resize_file(
        AtomicOutputFile::partial_path_for(final_path),
        name == "flight.d64" ? checkpoint.words->file_bytes : checkpoint.points_csv->file_bytes);
    fs::rename(AtomicOutputFile::partial_path_for(final_path), final_path);
  }
  resume(kFrames);
  expect_same_outputs();
}

TEST_F(FlightOutputsResume, ARefusedResumeLeavesEveryFileAsItWas) {
  // Issue 17: a resume refused for one damaged temporary had already cut back, and then removed,
  // the others, so the run could never be resumed. Now every temporary is checked first, and a
  // resumed temporary outlives a failure.
  kill_after(3);
  const fs::path las = dir_ / "interrupted" / "points.las.partial";
  ASSERT_TRUE(fs::exists(las));
  fs::resize_file(las, 10);  // shorter than the checkpoint says
  const auto before = files_under(dir_ / "interrupted");
  ASSERT_GE(before.size(), 6u);  // words, 3 point files, trajectory and the checkpoint, at least
  const std::optional<RunCheckpoint> checkpoint =
      read_run_checkpoint(run_checkpoint_path(dir_ / "interrupted"));
  ASSERT_TRUE(checkpoint.has_value());
  try {
    FlightOutputs outputs(options("interrupted", true), scene_, scan_, local_frame_, &*checkpoint);
    FAIL() << "resumed from a damaged points.las.partial";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("points.las.partial holds 10 bytes"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(files_under(dir_ / "interrupted"), before);
}

// Issue 45: a temporary replaced by a hard link to a file elsewhere (one that holds at least the
// checkpoint's bytes) was adopted, cut back and appended to. Now the resume refuses it and
// touches neither the file nor the folder.
TEST_F(FlightOutputsResume, AResumeRefusesAHardLinkPlantedAtATemporary) {
  kill_after(3);
  const fs::path csv = dir_ / "interrupted" / "points.csv.partial";
  const fs::path outside = dir_ / "outside.csv";
  fs::copy_file(csv, outside);
  std::ofstream(outside, std::ios::binary | std::ios::app) << "someone else's rows\n";
  const std::string precious = content(outside);
  fs::remove(csv);
  fs::create_hard_link(outside, csv);
  const auto before = files_under(dir_ / "interrupted");
  const std::optional<RunCheckpoint> checkpoint =
      read_run_checkpoint(run_checkpoint_path(dir_ / "interrupted"));
  ASSERT_TRUE(checkpoint.has_value());
  try {
    FlightOutputs outputs(options("interrupted", true), scene_, scan_, local_frame_, &*checkpoint);
    FAIL() << "resumed from a hard link to a file outside the folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(csv.string() + ": it has 2 names (hard links), not one"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(content(outside), precious);
  EXPECT_EQ(files_under(dir_ / "interrupted"), before);
}

TEST_F(FlightOutputsResume, ACheckpointChangedInOneDigitIsRefused) {
  // A plausible frame count, so only the checksum can tell: resuming it had given exit 0 and a
  // spliced row in points.csv. frames_done follows the header (20 bytes) and the run's JSON text
  // (a u64 length, then the text).
  kill_after(3);
  const fs::path path = run_checkpoint_path(dir_ / "interrupted");
  std::string text = content(path);
  BinaryRecordReader header(std::string_view(text).substr(20));
  const std::size_t at = 20 + 8 + header.get<std::uint64_t>();
  ASSERT_LT(at, text.size());
  ASSERT_EQ(text[at], '\x03');
  text[at] = '\x02';
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
  try {
    (void)read_run_checkpoint(path);
    FAIL() << "read a checkpoint changed by hand";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path.string() +
                                         ": damaged checkpoint (its checksum does not match its "
                                         "content); run without --resume to start over");
  }
}

TEST_F(FlightOutputsResume, ACheckpointWithoutAnOutputsStateIsRefused) {
  kill_after(3);
  std::optional<RunCheckpoint> checkpoint =
      read_run_checkpoint(run_checkpoint_path(dir_ / "interrupted"));
  ASSERT_TRUE(checkpoint.has_value());
  checkpoint->points_las.reset();
  try {
    FlightOutputs outputs(options("interrupted", true), scene_, scan_, local_frame_, &*checkpoint);
    FAIL() << "resumed without the LAS state";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no state for points.las"), std::string::npos)
        << e.what();
  }
}

TEST_F(FlightOutputsResume, AFreshRunRemovesAStaleCheckpointAndKeepsItsOwnUntilFinished) {
  const fs::path path = run_checkpoint_path(dir_ / "fresh");
  fs::create_directories(dir_ / "fresh");
  write_run_checkpoint(path, every_field_set());
  FlightOutputs outputs(options("fresh", true), scene_, scan_, local_frame_);
  EXPECT_FALSE(fs::exists(path));
  add_frames(outputs, 0, 2);
  const std::optional<RunCheckpoint> own = read_run_checkpoint(path);
  ASSERT_TRUE(own.has_value());
  EXPECT_EQ(own->frames_done, 2);
  EXPECT_EQ(own->run, nlohmann::json({{"test", "resume"}}));
  EXPECT_EQ(own->words->file_bytes, fs::file_size(dir_ / "fresh" / "flight.d64.partial"));
  const SyntheticFrame out_of_order = synthetic_frame(scan_, 3);
  EXPECT_THROW(outputs.add_frame(out_of_order.view(), out_of_order.start), Error);
  outputs.finish({});
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(FlightOutputsResume, ARunShorterThanTheIntervalWritesNoCheckpointEvenToFinish) {
  // Issue 16: a one-frame run spent a fifth of its time serialising every object's state into a
  // checkpoint at commit. Without one a resume starts from frame 0, to the same bytes. Seen here
  // through a finish that fails after the words are committed (summary.json's name is taken by
  // a folder): the short run leaves no checkpoint, a checkpointed one its finishing state.
  for (const bool checkpointed : {false, true}) {
    SCOPED_TRACE(checkpointed ? "checkpointed" : "short");
    const std::string folder = checkpointed ? "long" : "short";
    FlightOutputOptions o = options(folder, true);
    o.checkpoint_interval_s = checkpointed ? 0.0 : 1e9;
    fs::create_directories(dir_ / folder / "summary.json");
    FlightOutputs outputs(o, scene_, scan_, local_frame_);
    add_frames(outputs, 0, 2);
    EXPECT_THROW(outputs.finish({}), Error);
    const std::optional<RunCheckpoint> left =
        read_run_checkpoint(run_checkpoint_path(dir_ / folder));
    EXPECT_EQ(left.has_value(), checkpointed);
    if (left) EXPECT_TRUE(left->finishing);
  }
}

TEST_F(FlightOutputsResume, WithoutAFingerprintNoCheckpointIsWritten) {
  FlightOutputs outputs(options("plain", false), scene_, scan_, local_frame_);
  add_frames(outputs, 0, 2);
  EXPECT_FALSE(fs::exists(run_checkpoint_path(dir_ / "plain")));
  outputs.finish({});
}

}  // namespace
}  // namespace owsim
