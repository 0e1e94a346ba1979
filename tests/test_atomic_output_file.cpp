// Protects crash-safe output (DESIGN.md, INTERFACE.md): bytes live under `<final>.partial` until
// commit() renames them over the final name; without commit() nothing is left behind; every
// failure throws owsim::Error naming the path.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "test_recording_check_fixture.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

class AtomicOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fixture::fresh_directory(
        std::string("atomic_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override {
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(dir_);
  }
  static std::string content(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  // The one error message `make` throws, or "" if it does not throw.
  template <typename Make>
  static std::string error_of(Make make) {
    try {
      make();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(AtomicOutput, OnlyThePartialExistsBeforeCommitOnlyTheFinalAfter) {
  const fs::path final_path = dir_ / "points.csv";
  AtomicOutputFile file(final_path);
  EXPECT_EQ(file.partial_path(), dir_ / "points.csv.partial");
  file.write("frame,pulse\n");
  const char bytes[] = {'0', ',', '1', '\n'};
  file.write(bytes, sizeof bytes);
  EXPECT_EQ(file.bytes_written(), 16u);
  EXPECT_TRUE(fs::exists(file.partial_path()));
  EXPECT_FALSE(fs::exists(final_path));
  file.commit();
  EXPECT_TRUE(file.committed());
  EXPECT_FALSE(fs::exists(file.partial_path()));
  EXPECT_EQ(content(final_path), "frame,pulse\n0,1\n");
}

TEST_F(AtomicOutput, DestroyedWithoutCommitLeavesNeither) {
  const fs::path final_path = dir_ / "flight.d64";
  {
    AtomicOutputFile file(final_path);
    file.write(std::string(100'000, 'x'));
    EXPECT_TRUE(fs::exists(file.partial_path()));
  }
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_FALSE(fs::exists(AtomicOutputFile::partial_path_for(final_path)));
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(AtomicOutput, AnExistingFileIsReplacedOnlyAtCommit) {
  const fs::path final_path = dir_ / "summary.json";
  { std::ofstream(final_path) << "old"; }
  {
    AtomicOutputFile abandoned(final_path);
    abandoned.write("half-written");
  }
  EXPECT_EQ(content(final_path), "old");
  AtomicOutputFile file(final_path, {.sync_on_commit = false});
  file.write("new");
  EXPECT_EQ(content(final_path), "old");
  file.commit();
  EXPECT_EQ(content(final_path), "new");
}

TEST_F(AtomicOutput, WriteAtOverwritesAHeaderAndAppendingContinues) {
  const fs::path final_path = dir_ / "points.ply";
  AtomicOutputFile file(final_path);
  file.write("count=0000\n");
  file.write("data\n");
  file.write_at(6, "1234", 4);
  file.write("more\n");
  EXPECT_EQ(file.bytes_written(), 21u);
  const std::string message = error_of([&] { file.write_at(19, "xyz", 3); });
  EXPECT_NE(message.find(final_path.string()), std::string::npos) << message;
  file.commit();
  EXPECT_EQ(content(final_path), "count=1234\ndata\nmore\n");
}

TEST_F(AtomicOutput, MovedFileIsCommittedByItsNewOwner) {
  const fs::path final_path = dir_ / "moved.csv";
  AtomicOutputFile first(final_path);
  first.write("a");
  AtomicOutputFile second(std::move(first));
  second.write("b");
  second.commit();
  EXPECT_EQ(content(final_path), "ab");
}

TEST_F(AtomicOutput, WriteAfterCommitIsAnError) {
  AtomicOutputFile file(dir_ / "done.csv");
  file.commit();
  const std::string message = error_of([&] { file.write("late"); });
  EXPECT_NE(message.find("after commit"), std::string::npos) << message;
}

TEST_F(AtomicOutput, MissingDirectoryThrowsWithThePath) {
  const fs::path final_path = dir_ / "no_such_dir" / "flight.d64";
  const std::string message = error_of([&] { AtomicOutputFile file(final_path); });
  EXPECT_NE(message.find(final_path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
}

TEST_F(AtomicOutput, DirectoryThatIsAFileThrowsWithThePath) {
  { std::ofstream(dir_ / "plain") << "x"; }
  const fs::path final_path = dir_ / "plain" / "flight.d64";
  const std::string message = error_of([&] { AtomicOutputFile file(final_path); });
  EXPECT_NE(message.find(final_path.string()), std::string::npos) << message;
}

TEST_F(AtomicOutput, UnwritableDirectoryThrowsWithThePath) {
  const fs::path locked = dir_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read |
                              fs::perms::others_exec);
  const fs::path final_path = locked / "flight.d64";
  const auto check = [&] {
    const std::string message = error_of([&] { AtomicOutputFile file(final_path); });
    return message.find(final_path.string()) != std::string::npos &&
           message.find("Permission denied") != std::string::npos;
  };
  if (::access(locked.c_str(), W_OK) != 0) {
    EXPECT_TRUE(check());
    return;
  }
  // Root may write anywhere: try as the unprivileged user `nobody` in a child process.
  if (::geteuid() != 0) GTEST_SKIP() << "the locked directory is writable";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(2);
    ::_exit(check() ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error naming the path, 2: cannot become nobody";
}

// A full disk, simulated by pointing the temporary name at /dev/full: the error surfaces on a
// write or at commit, names the path, and nothing appears under the final name.
TEST_F(AtomicOutput, DiskFullThrowsWithThePath) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const fs::path final_path = dir_ / "flight.d64";
  fs::create_symlink("/dev/full", AtomicOutputFile::partial_path_for(final_path));
  const std::string message = error_of([&] {
    AtomicOutputFile file(final_path, {.sync_on_commit = false});
    file.write(std::string(1 << 20, 'w'));
    file.commit();
  });
  EXPECT_NE(message.find(final_path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(final_path));
}

}  // namespace
}  // namespace owsim
