// A file named by data from someone else is opened only when it is a local regular file inside
// the data's folder tree (io/files/confined_path.hpp, issue 33): names that reach the network,
// GDAL's virtual file systems, devices, FIFOs, folders, symbolic-link loops and anything outside
// the tree are refused before anything opens them.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "geometry/error.hpp"
#include "io/files/confined_path.hpp"

namespace owsim {
namespace {

namespace fs = std::filesystem;

std::string refusal(const fs::path& root, const std::string& given) {
  try {
    const fs::path accepted = confined_file(root, given);
    return "accepted " + accepted.string();
  } catch (const Error& e) {
    return e.what();
  }
}

class ConfinedPath : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(root() / "data/deeper");
    std::ofstream(root() / "scene.tif") << "x";
    std::ofstream(root() / "data/deeper/dem.tif") << "x";
    std::ofstream(dir_ / "beside.tif") << "x";  // in the parent of the root: outside
    fs::create_symlink("deeper/dem.tif", root() / "data/inside_link.tif");
    fs::create_symlink("../../beside.tif", root() / "data/outside_link.tif");
    fs::create_symlink("/dev/zero", root() / "zero.tif");
    fs::create_symlink("loop.tif", root() / "loop.tif");
    ASSERT_EQ(::mkfifo((root() / "fifo.tif").c_str(), 0600), 0);
  }
  [[nodiscard]] fs::path root() const { return dir_ / "scenario"; }

  test::TempDir dir_{"owsim_confined"};
};

TEST_F(ConfinedPath, FilesInTheTreeAreTheirCanonicalPaths) {
  const fs::path real_root = fs::canonical(root());
  EXPECT_EQ(confined_file(root(), "scene.tif"), real_root / "scene.tif");
  EXPECT_EQ(confined_file(root(), "data/deeper/dem.tif"), real_root / "data/deeper/dem.tif");
  EXPECT_EQ(confined_file(root(), "data/../scene.tif"), real_root / "scene.tif");
  EXPECT_EQ(confined_file(root(), "./data/inside_link.tif"), real_root / "data/deeper/dem.tif");
  EXPECT_EQ(confined_file(root(), (root() / "scene.tif").string()), real_root / "scene.tif");
}

TEST_F(ConfinedPath, NetworkVirtualAndConnectionNamesAreRefusedByTheirText) {
  for (const char* given : {"http://127.0.0.1:9/x.tif", "https://example.org/dem.tif", "ftp://h/x",
                            "file:///etc/passwd", "WMS:http://127.0.0.1:9/?", "PG:dbname=x",
                            "MEM:::DATAPOINTER=0x1,PIXELS=1,LINES=1", "GTIFF_DIR:1:scene.tif"}) {
    EXPECT_NE(refusal(root(), given).find("a URL or a connection string"), std::string::npos)
        << given;
  }
  for (const char* given : {"/vsicurl/http://127.0.0.1:9/x.tif", "/vsizip//etc/x.zip/a.tif",
                            "/vsimem/x.tif", "/vsis3/bucket/x.tif"}) {
    EXPECT_NE(refusal(root(), given).find("a GDAL virtual file system"), std::string::npos)
        << given;
  }
  EXPECT_EQ(refusal(root(), ""), "expected a file name, got ''");
  EXPECT_NE(refusal(root(), std::string("scene.tif\0x", 11)).find("NUL"), std::string::npos);
}

TEST_F(ConfinedPath, AnythingOutsideTheTreeOrNotARegularFileIsRefused) {
  for (const char* given : {"/etc/passwd", "/dev/zero", "../beside.tif", "data/../../beside.tif",
                            "data/outside_link.tif", "zero.tif"}) {
    EXPECT_NE(refusal(root(), given).find("outside the folder"), std::string::npos) << given;
  }
  EXPECT_NE(refusal(root(), "loop.tif").find("a symbolic link loop"), std::string::npos);
  EXPECT_NE(refusal(root(), "fifo.tif").find("not a regular file"), std::string::npos);
  EXPECT_NE(refusal(root(), "data").find("not a regular file"), std::string::npos);
  EXPECT_EQ(refusal(root(), "nothere.tif"), "no such file: " + (root() / "nothere.tif").string());
}

TEST(InsideTree, ComparesWholeComponents) {
  EXPECT_TRUE(inside_tree("/a/b", "/a/b"));
  EXPECT_TRUE(inside_tree("/a/b", "/a/b/c/d"));
  EXPECT_TRUE(inside_tree("/a/b/", "/a/b/c"));
  EXPECT_FALSE(inside_tree("/a/b", "/a/bc"));
  EXPECT_FALSE(inside_tree("/a/b", "/a"));
  EXPECT_FALSE(inside_tree("/a/b", "/x/b/c"));
}

}  // namespace
}  // namespace owsim
