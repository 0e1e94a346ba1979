// Protects truth.csv's rows (io/run/truth_csv.hpp, INTERFACE.md "Ground truth and detection
// evidence"): each row's cells against printf's correctly rounded fixed notation, ids quoted as
// RFC 4180 asks, ids of any length (longer than the encoder's block), many rows, and an object
// index the scene does not name refused.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <random>
#include <string>

#include "geometry/error.hpp"
#include "io/run/truth_csv.hpp"

namespace owsim {
namespace {

std::string fixed(double value, int decimals) {
  char text[512];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string cell(text);
  if (cell.find_first_not_of("-0.") == std::string::npos && cell.front() == '-') cell.erase(0, 1);
  return cell;
}

// The row as INTERFACE.md spells it, from printf and the id quoted by hand.
std::string expected_row(const FrameTruth& truth, const TruthRow& row, const std::string& cell,
                         const char* surface) {
  std::string text = std::to_string(truth.frame) + "," + fixed(truth.time_s, 9) + "," + cell + "," +
                     surface + "," + fixed(row.range_m, 3) + "," + fixed(row.alpha_deg, 4) + "," +
                     fixed(row.beta_deg, 4) + "," + (row.in_view ? "1" : "0") + "," +
                     std::to_string(row.returns) + "," + fixed(row.closing_speed_mps, 3) + ",";
  if (row.closing_speed_mps > 0.0) text += fixed(row.range_m / row.closing_speed_mps, 3);
  return text + "\n";
}

TEST(TruthCsv, RowsAreTheCellsInFixedDecimalsWithTheIdsQuoted) {
  Scene scene;
  scene.conductors.push_back({"span,1/\"a\"", {}, 0.01, 0.4});
  scene.cylinders.push_back({"pole-1", SurfaceClass::pole, {}, 0.2, 10.0, 0.3});
  scene.cylinders.push_back({std::string(40000, 't'), SurfaceClass::tree, {}, 2.0, 15.0, 0.3});
  const std::string cells[] = {"\"span,1/\"\"a\"\"\"", "pole-1", std::string(40000, 't')};
  const char* surfaces[] = {"wire", "pole", "tree"};
  const TruthCsvRows rows(scene);

  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  FrameTruth truth;
  truth.frame = 1234;
  truth.time_s = 411.333333333333;
  std::string expected;
  for (int r = 0; r < 3000; ++r) {  // ~45 blocks of rows, the long id every few rows
    TruthRow& row = truth.rows.emplace_back();
    row.object = static_cast<std::uint32_t>(r % 7 == 0 ? 2 : r % 2);
    row.range_m = 1300.0 * (0.5 + 0.5 * uniform(rng));
    row.alpha_deg = 90.0 * uniform(rng);
    row.beta_deg = 180.0 * uniform(rng);
    row.in_view = r % 3 == 0;
    row.returns = static_cast<std::uint64_t>(r % 5) * 1000;
    row.closing_speed_mps = r % 11 == 0 ? 0.0 : 60.0 * uniform(rng);
    expected += expected_row(truth, row, cells[row.object], surfaces[row.object]);
  }
  std::string text = "kept,";
  rows.encode(truth, text);
  EXPECT_EQ(text.substr(0, 5), "kept,");    // appended to what was there
  EXPECT_TRUE(text.substr(5) == expected);  // (no 40 kB diff printed)
  EXPECT_EQ(text.size(), expected.size() + 5);

  truth.rows.back().object = 3;
  std::string refused;
  EXPECT_THROW(rows.encode(truth, refused), Error);
}

}  // namespace
}  // namespace owsim
