// Protects the checks every input reader makes first (io/files/input_file.hpp, issue 17): a FIFO
// is refused at once instead of blocking, a device (/dev/zero) instead of being read forever, a
// directory and a symlink loop with one line, a file larger than its kind can be without reading
// it (a sparse file: no bytes on disk), and a terrain grid whose header claims more cells than its
// bytes can hold before anything is reserved for them.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/error.hpp"
#include "io/files/input_file.hpp"
#include "io/scenario/esri_ascii_grid.hpp"
#include "io/scenario/scenario_loader.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("owsim_input_file_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string error_of(auto&& call) {
    try {
      call();
    } catch (const Error& e) {
      return e.what();
    }
    return "accepted";
  }
  fs::path dir_;
};

TEST_F(InputFile, ARegularFileIsReadWhole) {
  std::ofstream(dir_ / "a.yaml") << "name: a\n";
  EXPECT_EQ(read_input_file(dir_ / "a.yaml", "YAML file", kMaxScenarioBytes), "name: a\n");
  EXPECT_EQ(require_input_file(dir_ / "a.yaml", "YAML file"), 8u);
}

TEST_F(InputFile, SpecialFilesAreRefusedWithoutReading) {
  const fs::path fifo = dir_ / "fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directory(dir_ / "folder.yaml");
  fs::create_symlink(dir_ / "loop_b", dir_ / "loop_a");
  fs::create_symlink(dir_ / "loop_a", dir_ / "loop_b");
  const auto read = [](const fs::path& path) {
    return [path] { (void)read_input_file(path, "YAML file", kMaxScenarioBytes); };
  };
  EXPECT_EQ(error_of(read(fifo)),
            fifo.string() + ": cannot read the YAML file: it is a FIFO, not a regular file");
  EXPECT_EQ(error_of(read("/dev/zero")),
            "/dev/zero: cannot read the YAML file: it is a device, not a regular file");
  EXPECT_EQ(error_of(read(dir_ / "folder.yaml")),
            (dir_ / "folder.yaml").string() +
                ": cannot read the YAML file: it is a directory, not a regular file");
  const std::string loop = error_of(read(dir_ / "loop_a"));
  EXPECT_EQ(loop.rfind((dir_ / "loop_a").string() + ": cannot read the YAML file: ", 0), 0u)
      << loop;
  EXPECT_NE(loop.find("symbolic links"), std::string::npos) << loop;
  EXPECT_EQ(error_of(read(dir_ / "missing.yaml")),
            (dir_ / "missing.yaml").string() + ": cannot read the YAML file: no such file");
  // The scenario loader goes through the same check: a FIFO scenario does not block.
  EXPECT_EQ(error_of([&] { (void)load_scenario(fifo); }),
            fifo.string() + ": cannot read the YAML file: it is a FIFO, not a regular file");
}

TEST_F(InputFile, AFileLargerThanItsKindIsRefusedUnread) {
  const fs::path big = dir_ / "big.yaml";
  std::ofstream(big).close();
  fs::resize_file(big, kMaxScenarioBytes + 1);  // sparse: nothing is written to disk
  EXPECT_EQ(error_of([&] { (void)read_input_file(big, "YAML file", kMaxScenarioBytes); }),
            big.string() +
                ": cannot read the YAML file: it holds 16777217 bytes, more than any "
                "YAML file (16 MiB)");
}

TEST_F(InputFile, AGridHeaderClaimingMoreCellsThanItsBytesIsRefused) {
  const fs::path grid = dir_ / "dem.asc";
  std::ofstream(grid) << "ncols 30000\nnrows 30000\nxllcenter 0\nyllcenter 0\ncellsize 1\n1 2\n";
  const std::string message = error_of([&] { (void)read_esri_ascii_grid(grid.string()); });
  EXPECT_NE(message.find("the header's 30000 columns × 30000 rows cannot fit in the file's"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace owsim
