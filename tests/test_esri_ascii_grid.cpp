// Protects the ESRI ASCII grid reader: corner and centre origins (corner + half a cell =
// centre), the north-row-first order, case-insensitive keys, NODATA, and malformed files each
// reported as "path:line: problem".
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "geometry/error.hpp"
#include "io/scenario/esri_ascii_grid.hpp"

namespace owsim {
namespace {

class EsriAsciiGrid : public testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path =
        testing::TempDir() + "owsim_esri_" + std::to_string(::getpid()) + "_" + name;
    std::ofstream(path, std::ios::binary) << text;
    written_.push_back(path);
    return path;
  }
  // The error message of reading `text`, or "no error".
  std::string error_of(const std::string& name, const std::string& text, std::string& path) {
    path = write(name, text);
    try {
      (void)read_esri_ascii_grid(path);
    } catch (const Error& error) {
      return error.what();
    }
    return "no error";
  }
  void TearDown() override {
    for (const std::string& path : written_) std::remove(path.c_str());
  }

 private:
  std::vector<std::string> written_;
};

const std::string kRows =
    "1 2 3 4\n"
    "5 -9999 11 13\n"
    "17 19 23 29.5\n";

TEST_F(EsriAsciiGrid, CornerAndCentreOriginsGiveTheSameGrid) {
  const HeightGrid corner =
      read_esri_ascii_grid(write("corner.asc",
                                 "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 10\n"
                                 "NODATA_value -9999\n" +
                                     kRows));
  const HeightGrid centre = read_esri_ascii_grid(
      write("centre.asc",
            "NCOLS 4\r\nNRows 3\r\nXLLCENTER 1005\r\nyllCenter 2005\r\nCellSize 10\r\n"
            "nodata_value -9999\r\n1 2 3 4 5 -9999\r\n11 13 17 19 23 +29.5\r\n"));
  for (const HeightGrid* grid : {&corner, &centre}) {
    EXPECT_EQ(grid->ncols, 4);
    EXPECT_EQ(grid->nrows, 3);
    EXPECT_EQ(grid->x_west_m, 1005.0);
    EXPECT_EQ(grid->y_south_m, 2005.0);
    EXPECT_EQ(grid->cellsize_m, 10.0);
    ASSERT_TRUE(grid->nodata.has_value());
    EXPECT_EQ(*grid->nodata, -9999.0);
    ASSERT_EQ(grid->heights.size(), 12u);
    EXPECT_EQ(grid->heights.front(), 1.0);
    EXPECT_EQ(grid->heights.back(), 29.5);
    EXPECT_TRUE(grid->is_nodata(grid->sample(1, 1)));
    EXPECT_NO_THROW(grid->validate("grid"));
    // The first row is the north one.
    EXPECT_EQ(grid->height_at(1005.0, 2005.0), 17.0);
    EXPECT_EQ(grid->height_at(1035.0, 2025.0), 4.0);
  }
}

TEST_F(EsriAsciiGrid, NodataIsOptional) {
  const HeightGrid grid = read_esri_ascii_grid(
      write("plain.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 2\n1 2\n3 4\n"));
  EXPECT_FALSE(grid.nodata.has_value());
  EXPECT_EQ(grid.height_at(1.0, 1.0), 3.0);
  EXPECT_DOUBLE_EQ(grid.height_at(2.0, 2.0), 2.5);
}

TEST_F(EsriAsciiGrid, MalformedFilesNameTheLine) {
  std::string path;
  // Missing ncols: reported where the data begin (line 5).
  std::string message =
      error_of("no_ncols.asc", "nrows 3\nxllcorner 0\nyllcorner 0\ncellsize 10\n" + kRows, path);
  EXPECT_EQ(message.rfind(path + ":5: ", 0), 0u) << message;
  EXPECT_NE(message.find("ncols"), std::string::npos) << message;
  // Too few values: reported at the last line.
  message =
      error_of("short.asc",
               "ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3 4\n5 6 7 8\n", path);
  EXPECT_EQ(message.rfind(path + ":7: ", 0), 0u) << message;
  // A non-number on line 9.
  message = error_of("word.asc",
                     "ncols 2\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 10\n"
                     "NODATA_value -1\n1 2\n3 4\n5 abc\n7 8\n",
                     path);
  EXPECT_EQ(message.rfind(path + ":9: ", 0), 0u) << message;
  EXPECT_NE(message.find("'abc'"), std::string::npos) << message;
  // Too many values.
  message = error_of("long.asc",
                     "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n5\n", path);
  EXPECT_EQ(message.rfind(path + ":8: ", 0), 0u) << message;
  // Both a corner and a centre origin.
  message = error_of(
      "both.asc", "ncols 2\nnrows 2\nxllcorner 0\nxllcenter 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n",
      path);
  EXPECT_EQ(message.rfind(path + ":7: ", 0), 0u) << message;
  // A repeated key, an unknown key, a bad cellsize, a fractional ncols.
  message = error_of("twice.asc", "ncols 2\nncols 2\n", path);
  EXPECT_EQ(message.rfind(path + ":2: ", 0), 0u) << message;
  message = error_of("unknown.asc", "ncols 2\nnrows 2\nzllcorner 0\n", path);
  EXPECT_EQ(message.rfind(path + ":3: ", 0), 0u) << message;
  message = error_of("cellsize.asc",
                     "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -1\n1 2\n3 4\n", path);
  EXPECT_EQ(message.rfind(path + ":6: ", 0), 0u) << message;
  message = error_of("fraction.asc",
                     "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", path);
  EXPECT_EQ(message.rfind(path + ":6: ", 0), 0u) << message;
  // An empty file: the header is missing.
  message = error_of("empty.asc", "", path);
  EXPECT_EQ(message.rfind(path + ":0: ", 0), 0u) << message;
  // A file that is not there.
  EXPECT_THROW((void)read_esri_ascii_grid(testing::TempDir() + "owsim_no_such_grid.asc"), Error);
}

}  // namespace
}  // namespace owsim
