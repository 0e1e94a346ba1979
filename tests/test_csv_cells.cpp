// Protects the CSV number cells (io/files/csv_cells.hpp): the integer path of write_csv_fixed
// gives std::to_chars's text (fixed, correctly rounded) for random values of every magnitude and
// 0..9 decimals, exact ties and their neighbours, zeros of either sign, subnormals and values
// past its range; NaN and infinities leave the cell empty.
#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "io/files/csv_cells.hpp"

namespace owsim {
namespace {

std::string fixed(double value, int decimals) {
  std::array<char, kCsvNumberMaxChars> text{};
  return {text.data(), write_csv_fixed(text.data(), value, decimals)};
}

// The reference: std::to_chars, a formatted zero without its sign.
std::string reference(double value, int decimals) {
  std::array<char, kCsvNumberMaxChars> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value,
                                    std::chars_format::fixed, decimals);
  std::string s(text.data(), result.ptr);
  if (s.front() == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

TEST(CsvCells, FixedEqualsToCharsForRandomValues) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-14, 10), decimals(0, 9);
  for (int i = 0; i < 400'000; ++i) {
    const double value = mantissa(random) * std::pow(10.0, exponent(random));
    const int d = decimals(random);
    ASSERT_EQ(fixed(value, d), reference(value, d)) << value << " " << d;
  }
}

TEST(CsvCells, FixedTiesZerosAndEdges) {
  for (int d = 0; d <= 9; ++d) {
    for (const double base : {0.5, 1.5, 2.5, 0.25, 0.125, 0.0625, 1.0 / 1024, 3.0 / 2048}) {
      for (const double value : {base, -base, std::nextafter(base, 0.0), std::nextafter(base, 1.0),
                                 base * 1e3, base / 1e4}) {
        ASSERT_EQ(fixed(value, d), reference(value, d)) << value << " " << d;
      }
    }
    for (const double value : {0.0, -0.0, -1e-12, 4.9e-324, -4.9e-324, 1e-300, 0x1p30 - 0.5, 0x1p30,
                               -0x1p30, 1e20, -123456789.123456789, 48.688386101499996}) {
      ASSERT_EQ(fixed(value, d), reference(value, d)) << value << " " << d;
    }
  }
  EXPECT_EQ(fixed(-0.00004, 4), "0.0000");
  EXPECT_EQ(fixed(-0.00005000001, 4), "-0.0001");
  EXPECT_EQ(fixed(48.6883861015, 9), "48.688386102");  // 0.5 in the tenth decimal is no tie here
  EXPECT_EQ(fixed(std::numeric_limits<double>::quiet_NaN(), 4), "");
  EXPECT_EQ(fixed(std::numeric_limits<double>::infinity(), 4), "");
}

}  // namespace
}  // namespace owsim
