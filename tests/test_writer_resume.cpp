// Protects the writers' resume after a kill (`owsim run --resume`, io/files/writer_checkpoint.hpp):
// each writer's checkpoint, carried through the checkpoint file, and the temporary the killed
// writer left (with bytes written after the checkpoint) give, once resumed and finished, the bytes
// of an uninterrupted writer — words, points.csv, points.las (counts, bounds, creation day),
// points.ply, trajectory.csv; and AtomicOutputFile::resume cuts back, appends and refuses a
// missing or short temporary.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/geodetic_frame.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/points/las_writer.hpp"
#include "io/points/ply_writer.hpp"
#include "io/points/points_csv_writer.hpp"
#include "io/recording/word_file.hpp"
#include "io/run/run_checkpoint.hpp"
#include "io/trajectory/trajectory_csv_writer.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

const Geodetic kOrigin{48.6881, 10.8447, 450.0};

class WriterResume : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("owsim_writer_resume_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "reference");
    fs::create_directories(dir_ / "resumed");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The same file name in the uninterrupted and the resumed folder.
  [[nodiscard]] fs::path reference(const std::string& name) const {
    return dir_ / "reference" / name;
  }
  [[nodiscard]] fs::path resumed(const std::string& name) const { return dir_ / "resumed" / name; }

  // Saves the reference writer's temporary as it stands at a checkpoint.
  void save_temporary(const std::string& name) const {
    fs::copy_file(AtomicOutputFile::partial_path_for(reference(name)), dir_ / "saved",
                  fs::copy_options::overwrite_existing);
  }
  // What a killed writer leaves in the resumed folder: the saved temporary plus bytes it wrote
  // after the checkpoint.
  void leave_killed_temporary(const std::string& name) const {
    const fs::path partial = AtomicOutputFile::partial_path_for(resumed(name));
    fs::copy_file(dir_ / "saved", partial, fs::copy_options::overwrite_existing);
    std::ofstream(partial, std::ios::binary | std::ios::app) << "written after the checkpoint";
  }
  // A checkpoint as it comes back from the checkpoint file.
  [[nodiscard]] RunCheckpoint through_file(const RunCheckpoint& checkpoint) const {
    const fs::path path = run_checkpoint_path(dir_);
    write_run_checkpoint(path, checkpoint);
    const std::optional<RunCheckpoint> read = read_run_checkpoint(path);
    if (!read) throw std::runtime_error("the checkpoint file is missing");
    return *read;
  }

  fs::path dir_;
};

std::string file_content(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Whether the two files hold the same bytes; if not, says where they first differ.
::testing::AssertionResult same_bytes(const fs::path& a, const fs::path& b) {
  const std::string bytes_a = file_content(a), bytes_b = file_content(b);
  if (bytes_a == bytes_b) return ::testing::AssertionSuccess();
  std::size_t at = 0;
  while (at < bytes_a.size() && at < bytes_b.size() && bytes_a[at] == bytes_b[at]) ++at;
  return ::testing::AssertionFailure() << a << " (" << bytes_a.size() << " bytes) and " << b << " ("
                                       << bytes_b.size() << " bytes) differ at byte " << at;
}

// Returns around the origin within ±spread_m, every class (and unknown), first and second
// returns, NaN energies now and then.
std::vector<PointRecord> points_around(int count, double spread_m, unsigned seed) {
  const LocalFrame frame(kOrigin);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> horizontal(-spread_m, spread_m), up(-20.0, 150.0),
      unit(0.0, 1.0);
  std::vector<PointRecord> points;
  for (int k = 0; k < count; ++k) {
    PointRecord& p = points.emplace_back();
    p.frame = k / 50;
    p.pulse = k % 50;
    p.line = k % 159;
    p.fiber = 1 + k % 127;
    p.number_of_returns = k % 5 == 0 ? 2 : 1;
    p.return_number = p.number_of_returns == 2 && k % 2 == 0 ? 2 : 1;
    p.time_s = 0.001 * k + unit(rng) * 1e-4;
    p.range_m = 50.0 + 1000.0 * unit(rng);
    p.counter = static_cast<std::uint16_t>(p.range_m / 0.6);
    p.enu_m = {horizontal(rng), horizontal(rng), up(rng)};
    p.geodetic = frame.geodetic_from_enu(p.enu_m);
    if (k % 9 != 0) p.surface = static_cast<SurfaceClass>(k % 4);
    p.object_index = k % 4 == 3 ? kNoObject : static_cast<std::uint32_t>(k % 3);
    p.energy_rel = k % 11 == 0 ? std::numeric_limits<double>::quiet_NaN() : 0.3 * unit(rng);
    p.incidence_deg = 90.0 * unit(rng);
    p.scan_angle_deg = -18.0 + 36.0 * unit(rng);
  }
  return points;
}

TEST_F(WriterResume, AtomicOutputFileResumeCutsBackAndAppends) {
  {
    std::ofstream(AtomicOutputFile::partial_path_for(resumed("a.bin")), std::ios::binary)
        << "kept|dropped";
  }
  AtomicOutputFile file = AtomicOutputFile::resume(resumed("a.bin"), 5, {.sync_on_commit = false});
  EXPECT_EQ(file.bytes_written(), 5u);
  file.write("more");
  file.write_at(0, "K", 1);
  file.commit();
  EXPECT_EQ(file_content(resumed("a.bin")), "Kept|more");
}

TEST_F(WriterResume, AtomicOutputFileRefusesAMissingOrShortTemporaryAndKeepsIt) {
  try {
    (void)AtomicOutputFile::resume(resumed("missing.bin"), 0);
    FAIL() << "resumed a missing temporary";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(resumed("missing.bin").string()), std::string::npos)
        << e.what();
  }
  const fs::path partial = AtomicOutputFile::partial_path_for(resumed("short.bin"));
  { std::ofstream(partial, std::ios::binary) << "abc"; }
  try {
    (void)AtomicOutputFile::resume(resumed("short.bin"), 4);
    FAIL() << "resumed a temporary shorter than the checkpoint";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds 3 bytes, the checkpoint 4"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(file_content(partial), "abc");  // a refused resume leaves the temporary as it was
}

TEST_F(WriterResume, WordsContinueByteForByte) {
  std::vector<std::uint64_t> words(5000);
  std::mt19937_64 rng(7);
  for (std::uint64_t& word : words) word = rng();
  const auto first = std::span<const std::uint64_t>(words).first(2003);
  const auto second = std::span<const std::uint64_t>(words).subspan(2003);
  constexpr std::size_t kBuffer = 1000;  // flushes in the middle of both halves

  MilowsWordWriter writer(reference("flight.d64"), {.sync_on_commit = false}, kBuffer);
  writer.write(first);
  RunCheckpoint checkpoint;
  checkpoint.words = writer.checkpoint();
  EXPECT_EQ(*checkpoint.words, (WriterCheckpoint{2003 * 8, 2003}));
  save_temporary("flight.d64");
  writer.write(second);
  writer.commit();

  leave_killed_temporary("flight.d64");
  MilowsWordWriter again = MilowsWordWriter::resume(
      resumed("flight.d64"), *through_file(checkpoint).words, {.sync_on_commit = false}, kBuffer);
  again.write(second);
  EXPECT_EQ(again.words_written(), 5000u);
  again.commit();
  EXPECT_TRUE(same_bytes(reference("flight.d64"), resumed("flight.d64")));
}

TEST_F(WriterResume, WordsRefuseACheckpointInsideAWord) {
  const fs::path partial = AtomicOutputFile::partial_path_for(resumed("flight.hellas"));
  { std::ofstream(partial, std::ios::binary) << std::string(12, 'w'); }
  try {
    (void)HellasWordWriter::resume(resumed("flight.hellas"), {10, 3});
    FAIL() << "resumed 10 bytes as 3 words";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("10 bytes are not 3 words"), std::string::npos)
        << e.what();
  }
}

TEST_F(WriterResume, PointsCsvContinuesByteForByte) {
  const std::vector<PointRecord> first = points_around(700, 800.0, 1);
  const std::vector<PointRecord> second = points_around(900, 1500.0, 2);
  const std::vector<std::string> ids = {"line-a/1", "pole, \"p1\"", "tree"};

  PointsCsvWriter writer(reference("points.csv"), ids, {.sync_on_commit = false});
  writer.write(first);
  RunCheckpoint checkpoint;
  checkpoint.points_csv = writer.checkpoint();
  save_temporary("points.csv");
  writer.write(second);
  writer.finish();

  leave_killed_temporary("points.csv");
  PointsCsvWriter again = PointsCsvWriter::resume(
      resumed("points.csv"), ids, *through_file(checkpoint).points_csv, {.sync_on_commit = false});
  again.write(second);
  EXPECT_EQ(again.points_written(), 1600u);
  again.finish();
  EXPECT_TRUE(same_bytes(reference("points.csv"), resumed("points.csv")));
}

TEST_F(WriterResume, LasContinuesWithItsCountsBoundsAndCreationDay) {
  // The first half reaches further out: the finished header's bounds are the checkpoint's.
  const std::vector<PointRecord> first = points_around(600, 3000.0, 3);
  const std::vector<PointRecord> second = points_around(800, 300.0, 4);
  LasWriterOptions options;
  options.origin = kOrigin;
  options.creation_date = LasDate{100, 2020};
  options.file.sync_on_commit = false;

  LasWriter writer(reference("points.las"), options);
  writer.write(first);
  RunCheckpoint checkpoint;
  checkpoint.points_las = writer.checkpoint();
  EXPECT_EQ(checkpoint.points_las->file.records, 600u);
  save_temporary("points.las");
  writer.write(second);
  writer.finish();

  leave_killed_temporary("points.las");
  LasWriterOptions next_day = options;
  next_day.creation_date = LasDate{101, 2020};  // the checkpoint's day wins
  LasWriter again =
      LasWriter::resume(resumed("points.las"), next_day, *through_file(checkpoint).points_las);
  again.write(second);
  again.finish();
  EXPECT_TRUE(same_bytes(reference("points.las"), resumed("points.las")));
}

TEST_F(WriterResume, LasRefusesACheckpointWhoseCountsDoNotFitItsSize) {
  LasWriterOptions options;
  options.origin = kOrigin;
  options.file.sync_on_commit = false;
  LasWriter writer(reference("points.las"), options);
  writer.write(points_around(10, 100.0, 5));
  LasCheckpoint checkpoint = writer.checkpoint();
  save_temporary("points.las");
  leave_killed_temporary("points.las");
  checkpoint.points_by_return[0] += 1;
  EXPECT_THROW((void)LasWriter::resume(resumed("points.las"), options, checkpoint), Error);
}

TEST_F(WriterResume, PlyContinuesAndCountsEveryVertex) {
  const std::vector<PointRecord> first = points_around(500, 800.0, 6);
  const std::vector<PointRecord> second = points_around(650, 800.0, 7);

  PlyWriter writer(reference("points.ply"), {.sync_on_commit = false});
  writer.write(first);
  RunCheckpoint checkpoint;
  checkpoint.points_ply = writer.checkpoint();
  save_temporary("points.ply");
  writer.write(second);
  writer.finish();
  EXPECT_NE(file_content(reference("points.ply")).find("element vertex 1150\n"), std::string::npos);

  leave_killed_temporary("points.ply");
  PlyWriter again = PlyWriter::resume(resumed("points.ply"), *through_file(checkpoint).points_ply,
                                      {.sync_on_commit = false});
  again.write(second);
  again.finish();
  EXPECT_TRUE(same_bytes(reference("points.ply"), resumed("points.ply")));
}

TEST_F(WriterResume, TrajectoryCsvContinuesByteForByte) {
  const LocalFrame frame(kOrigin);
  std::vector<Pose> poses(40);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const double t = static_cast<double>(i) / 3.0;
    poses[i].time_s = t;
    poses[i].position_enu_m = {40.0 * t - 1200.0, 3.0 * t, 100.0 + 0.1 * t};
    poses[i].attitude = {0.5 * std::sin(t), -4.0, 90.0 + t};
  }
  const auto first = std::span<const Pose>(poses).first(17);
  const auto second = std::span<const Pose>(poses).subspan(17);

  TrajectoryCsvWriter writer(reference("trajectory.csv"), frame, {.sync_on_commit = false});
  writer.write(first);
  RunCheckpoint checkpoint;
  checkpoint.trajectory = writer.checkpoint();
  save_temporary("trajectory.csv");
  writer.write(second);
  writer.finish();

  leave_killed_temporary("trajectory.csv");
  TrajectoryCsvWriter again =
      TrajectoryCsvWriter::resume(resumed("trajectory.csv"), frame,
                                  *through_file(checkpoint).trajectory, {.sync_on_commit = false});
  again.write(second);
  EXPECT_EQ(again.rows_written(), 40u);
  again.finish();
  EXPECT_TRUE(same_bytes(reference("trajectory.csv"), resumed("trajectory.csv")));
}

}  // namespace
}  // namespace owsim
