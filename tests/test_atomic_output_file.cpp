// Protects crash-safe output (DESIGN.md, INTERFACE.md): bytes live under `<final>.partial` until
// commit() renames them over the final name; without commit() nothing is left behind; every
// failure throws owsim::Error naming the path. And safe output (issue 45): nothing planted at the
// temporary's name — a symbolic or hard link, a FIFO, a device, a directory — is written through,
// resumed from or reopened, and no link is followed where owsim makes a folder of its own.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/output_open.hpp"
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

// Each kWritebackStep bytes, a file synced at commit hands what it holds to the kernel (and starts
// its writeback): the temporary then holds every byte written, with no flush() asked for; a
// header overwritten afterwards and the bytes appended still come out whole.
TEST_F(AtomicOutput, EveryWritebackStepHandsTheBytesToTheKernel) {
  const std::string piece(1000, 'x');
  const std::uint64_t step = AtomicOutputFile::kWritebackStep;
  for (const bool synced : {true, false}) {
    const fs::path final_path = dir_ / (synced ? "synced.d64" : "unsynced.d64");
    AtomicOutputFile file(final_path, AtomicOutputOptions{synced});
    file.write("head");
    while (file.bytes_written() + piece.size() < step) file.write(piece);
    EXPECT_LT(fs::file_size(file.partial_path()), file.bytes_written());  // stdio holds some
    file.write(piece);  // past the step
    if (synced) {
      EXPECT_EQ(fs::file_size(file.partial_path()), file.bytes_written());
    } else {
      EXPECT_LT(fs::file_size(file.partial_path()), file.bytes_written());
    }
    file.write_at(0, "HEAD", 4);
    file.write("tail");
    const std::uint64_t total = file.bytes_written();
    file.commit();
    const std::string bytes = content(final_path);
    ASSERT_EQ(bytes.size(), total);
    EXPECT_EQ(bytes.substr(0, 5), "HEADx");
    EXPECT_EQ(bytes.substr(bytes.size() - 5), "xtail");
    EXPECT_EQ(bytes.find_first_not_of('x', 4), bytes.size() - 4);
  }
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

// A full disk: the error surfaces on a write or at commit, names the path, and nothing appears
// under the final name. Simulated with a file size limit (EFBIG) in a child process.
TEST_F(AtomicOutput, AWriteFailureThrowsWithThePath) {
  const fs::path final_path = dir_ / "flight.d64";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{64 * 1024, 64 * 1024};
    if (std::signal(SIGXFSZ, SIG_IGN) == SIG_ERR || ::setrlimit(RLIMIT_FSIZE, &limit) != 0) {
      ::_exit(2);
    }
    const std::string message = error_of([&] {
      AtomicOutputFile file(final_path, {.sync_on_commit = false});
      file.write(std::string(1 << 20, 'w'));
      file.commit();
    });
    ::_exit(message.find(final_path.string()) != std::string::npos &&
                    message.find("File too large") != std::string::npos && !fs::exists(final_path)
                ? 0
                : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error naming the path, 2: cannot set the limit";
  EXPECT_FALSE(fs::exists(final_path));
}

// Issue 45: what sits at `<final>.partial` before owsim writes — planted in a shared output
// folder — is removed, never written through; the final name becomes a regular file of owsim's
// bytes.
class PlantedPartial : public AtomicOutput {
 protected:
  void SetUp() override {
    AtomicOutput::SetUp();
    outside_ = dir_.parent_path() / (dir_.filename().string() + "_outside");
    fs::remove_all(outside_);
    fs::create_directories(outside_);
    victim_ = outside_ / "victim.txt";
    std::ofstream(victim_) << "precious";
  }
  void TearDown() override {
    fs::remove_all(outside_);
    AtomicOutput::TearDown();
  }
  // Writes `bytes` to `final_path` through an AtomicOutputFile.
  static void write_file(const fs::path& final_path, const std::string& bytes) {
    AtomicOutputFile file(final_path, {.sync_on_commit = false});
    file.write(bytes);
    file.commit();
  }
  // The final name holds `bytes` as a regular file, no temporary is left, the victim is unchanged.
  void expect_written(const fs::path& final_path, const std::string& bytes) const {
    EXPECT_EQ(fs::symlink_status(final_path).type(), fs::file_type::regular);
    EXPECT_EQ(fs::hard_link_count(final_path), 1u);
    EXPECT_EQ(content(final_path), bytes);
    EXPECT_FALSE(fs::exists(fs::symlink_status(AtomicOutputFile::partial_path_for(final_path))));
    EXPECT_EQ(content(victim_), "precious");
    EXPECT_EQ(fs::hard_link_count(victim_), 1u);
  }

  fs::path outside_;
  fs::path victim_;
};

TEST_F(PlantedPartial, ASymbolicLinkToAFileOutsideIsNotFollowed) {
  const fs::path final_path = dir_ / "pd.csv";
  fs::create_symlink(victim_, AtomicOutputFile::partial_path_for(final_path));
  write_file(final_path, "owsim's bytes");
  expect_written(final_path, "owsim's bytes");
}

TEST_F(PlantedPartial, ADanglingSymbolicLinkCreatesNothingOutside) {
  const fs::path final_path = dir_ / "report.html";
  const fs::path target = outside_ / "new.txt";
  fs::create_symlink(target, AtomicOutputFile::partial_path_for(final_path));
  write_file(final_path, "<html>");
  expect_written(final_path, "<html>");
  EXPECT_FALSE(fs::exists(target));
}

TEST_F(PlantedPartial, ASymbolicLinkToADeviceIsNotFollowed) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const fs::path final_path = dir_ / "flight.d64";
  fs::create_symlink("/dev/full", AtomicOutputFile::partial_path_for(final_path));
  write_file(final_path, std::string(100'000, 'w'));
  expect_written(final_path, std::string(100'000, 'w'));
}

TEST_F(PlantedPartial, AHardLinkToAFileOutsideIsNotWrittenThrough) {
  const fs::path final_path = dir_ / "scenario.yaml";
  fs::create_hard_link(victim_, AtomicOutputFile::partial_path_for(final_path));
  ASSERT_EQ(fs::hard_link_count(victim_), 2u);
  write_file(final_path, "name: x\n");
  expect_written(final_path, "name: x\n");
}

TEST_F(PlantedPartial, AFifoNeitherHangsNorStays) {
  const fs::path final_path = dir_ / "pd.svg";
  ASSERT_EQ(::mkfifo(AtomicOutputFile::partial_path_for(final_path).c_str(), 0666), 0);
  ::alarm(30);  // a write through the FIFO would block forever: fail instead
  write_file(final_path, "<svg/>");
  ::alarm(0);
  expect_written(final_path, "<svg/>");
}

TEST_F(PlantedPartial, ADirectoryIsRefusedInOneLineAndKept) {
  const fs::path final_path = dir_ / "roc.json";
  const fs::path partial = AtomicOutputFile::partial_path_for(final_path);
  fs::create_directories(partial / "inside");
  const std::string message = error_of([&] { write_file(final_path, "{}"); });
  EXPECT_EQ(message,
            final_path.string() + ": cannot create " + partial.string() + ": it is a directory");
  EXPECT_TRUE(fs::is_directory(partial / "inside"));
  EXPECT_FALSE(fs::exists(final_path));
}

TEST_F(PlantedPartial, AnExistingFinalLinkIsReplacedNotFollowed) {
  const fs::path final_path = dir_ / "summary.json";
  fs::create_symlink(victim_, final_path);
  write_file(final_path, "{}");
  expect_written(final_path, "{}");
}

// A resume adopts only the regular file an owsim writer left, never what a link names: the
// victim is neither cut back nor appended to.
TEST_F(PlantedPartial, AResumeThroughASymbolicLinkIsRefused) {
  const fs::path final_path = dir_ / "points.csv";
  const fs::path partial = AtomicOutputFile::partial_path_for(final_path);
  fs::create_symlink(victim_, partial);
  const std::string expected = final_path.string() + ": cannot resume from " + partial.string() +
                               ": it is a symbolic link (not followed)";
  EXPECT_EQ(error_of([&] { AtomicOutputFile::require_resumable(final_path, 3); }), expected);
  EXPECT_EQ(error_of([&] {
              AtomicOutputFile file = AtomicOutputFile::resume(final_path, 3);
              file.write("XX");
              file.commit();
            }),
            expected);
  EXPECT_EQ(content(victim_), "precious");
  EXPECT_EQ(fs::symlink_status(partial).type(), fs::file_type::symlink);
  EXPECT_FALSE(fs::exists(fs::symlink_status(final_path)));
}

TEST_F(PlantedPartial, AResumeOfAHardLinkAFifoOrAnotherUsersFileIsRefused) {
  const fs::path final_path = dir_ / "points.las";
  const fs::path partial = AtomicOutputFile::partial_path_for(final_path);
  const auto refusal = [&] {
    return error_of([&] { (void)AtomicOutputFile::resume(final_path, 3); });
  };
  fs::create_hard_link(victim_, partial);
  EXPECT_EQ(refusal(), final_path.string() + ": cannot resume from " + partial.string() +
                           ": it has 2 names (hard links), not one");
  EXPECT_EQ(content(victim_), "precious");
  fs::remove(partial);

  ASSERT_EQ(::mkfifo(partial.c_str(), 0666), 0);
  ::alarm(30);
  EXPECT_EQ(refusal(), final_path.string() + ": cannot resume from " + partial.string() +
                           ": it is a FIFO, not a regular file");
  ::alarm(0);
  fs::remove(partial);

  std::ofstream(partial) << "abcdef";
  if (::geteuid() == 0) {
    ASSERT_EQ(::chown(partial.c_str(), 65534, 65534), 0);
    EXPECT_EQ(refusal(), final_path.string() + ": cannot resume from " + partial.string() +
                             ": it belongs to another user");
    ASSERT_EQ(::chown(partial.c_str(), 0, 0), 0);
  }
  // The writer's own file resumes: cut to the checkpoint, appended to.
  AtomicOutputFile file = AtomicOutputFile::resume(final_path, 3, {.sync_on_commit = false});
  file.write("X");
  file.commit();
  EXPECT_EQ(content(final_path), "abcX");
}

// The other processes of a distributed run reopen the temporary process 0 created by name: only
// that regular file, never a link put in its place.
TEST_F(PlantedPartial, ReopeningATemporaryRefusesALink) {
  const fs::path final_path = dir_ / "flight.d64";
  AtomicOutputFile file(final_path, {.sync_on_commit = false});
  file.write("0123");
  file.flush();
  const int fd = open_output_file(file.partial_path(), O_WRONLY, "here", "cannot open");
  ASSERT_GE(fd, 0);
  EXPECT_EQ(::pwrite(fd, "AB", 2, 4), 2);
  ::close(fd);
  file.skip(2);
  file.commit();
  EXPECT_EQ(content(final_path), "0123AB");

  const fs::path planted = dir_ / "points.csv.partial";
  fs::create_symlink(victim_, planted);
  EXPECT_EQ(error_of([&] { (void)open_output_file(planted, O_WRONLY, "here", "cannot open"); }),
            "here: cannot open " + planted.string() + ": it is a symbolic link (not followed)");
  EXPECT_EQ(content(victim_), "precious");
}

// The folders owsim names inside an output folder are made, or taken when they are folders, but
// never followed when a link sits at their name.
TEST_F(PlantedPartial, AnOutputSubfolderIsNeverALink) {
  make_output_subfolder(dir_ / "quicklook");
  EXPECT_TRUE(fs::is_directory(fs::symlink_status(dir_ / "quicklook")));
  make_output_subfolder(dir_ / "quicklook");  // already there: taken
  make_output_subfolders(dir_, "inputs/1");
  EXPECT_TRUE(fs::is_directory(fs::symlink_status(dir_ / "inputs/1")));

  fs::create_directory_symlink(outside_, dir_ / "007");
  EXPECT_EQ(error_of([&] { make_output_subfolder(dir_ / "007"); }),
            (dir_ / "007").string() +
                ": cannot create the folder: it is a symbolic link (not "
                "followed)");
  fs::create_directory_symlink(outside_, dir_ / "inputs/2");
  EXPECT_EQ(error_of([&] { make_output_subfolders(dir_, "inputs/2/sub"); }),
            (dir_ / "inputs/2").string() +
                ": cannot create the folder: it is a symbolic link (not "
                "followed)");
  EXPECT_FALSE(fs::exists(outside_ / "sub"));
  std::ofstream(dir_ / "plain") << "x";
  EXPECT_EQ(error_of([&] { make_output_subfolder(dir_ / "plain"); }),
            (dir_ / "plain").string() + ": cannot create the folder: it is a file");
}

}  // namespace
}  // namespace owsim
