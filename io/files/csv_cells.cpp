#include "io/files/csv_cells.hpp"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "geometry/error.hpp"

namespace owsim {
namespace {

__extension__ typedef unsigned __int128 Uint128;  // GCC and clang: exact 53 × 30-bit products

constexpr std::array<std::uint64_t, 10> kPowersOfTen = {
    1, 10, 100, 1'000, 10'000, 100'000, 1'000'000, 10'000'000, 100'000'000, 1'000'000'000};

// Drops the sign of a formatted zero ("-0.0000" becomes "0.0000") so the output has one
// spelling; returns the end.
char* unsigned_zero(char* first, char* last) {
  if (*first != '-') return last;
  for (const char* c = first + 1; c != last; ++c) {
    if (*c != '0' && *c != '.') return last;
  }
  std::memmove(first, first + 1, static_cast<std::size_t>(last - first - 1));
  return last - 1;
}

// "00" … "99".
constexpr std::array<char, 200> kDigitPairs = [] {
  std::array<char, 200> pairs{};
  for (int i = 0; i < 100; ++i) {
    pairs[static_cast<std::size_t>(2 * i)] = static_cast<char>('0' + i / 10);
    pairs[static_cast<std::size_t>(2 * i + 1)] = static_cast<char>('0' + i % 10);
  }
  return pairs;
}();

// The decimal digits of n, written ending at `end` (backwards); returns where they start.
char* digits_before(char* end, std::uint64_t n) {
  while (n >= 100) {
    const auto pair = static_cast<std::size_t>(2 * (n % 100));
    n /= 100;
    *--end = kDigitPairs[pair + 1];
    *--end = kDigitPairs[pair];
  }
  if (n >= 10) {
    const auto pair = static_cast<std::size_t>(2 * n);
    *--end = kDigitPairs[pair + 1];
    *--end = kDigitPairs[pair];
  } else {
    *--end = static_cast<char>('0' + n);
  }
  return end;
}

constexpr std::array<std::uint64_t, 20> kDecimalLimits = [] {
  std::array<std::uint64_t, 20> limits{};
  std::uint64_t p = 1;
  for (std::size_t i = 0; i < limits.size(); ++i, p *= 10) limits[i] = p;
  return limits;
}();

// How many decimal digits n has (1 for 0): t = ⌊bit width · log10 2⌋ is ⌊log10⌋ or one more,
// corrected by one comparison (Anderson, "Bit Twiddling Hacks", IntegerLog10).
int digit_count(std::uint64_t n) {
  const std::uint64_t m = n | 1;
  const int t = (static_cast<int>(std::bit_width(m)) * 1233) >> 12;
  return t + 1 - (m < kDecimalLimits[static_cast<std::size_t>(t)] ? 1 : 0);
}

// q / 10^D as "whole.fraction" with exactly D decimals, written at out; returns the end. The
// divisions are by constants, so multiplications.
template <int D>
char* scaled_digits(char* out, std::uint64_t q) {
  constexpr std::uint64_t kScale = kPowersOfTen[D];
  std::uint64_t whole = q / kScale, fraction = q % kScale;
  char* end = out + digit_count(whole) + (D > 0 ? D + 1 : 0);
  char* at = end;
  for (int i = 0; i + 1 < D; i += 2) {
    const auto pair = static_cast<std::size_t>(2 * (fraction % 100));
    fraction /= 100;
    *--at = kDigitPairs[pair + 1];
    *--at = kDigitPairs[pair];
  }
  if constexpr (D % 2 == 1) *--at = static_cast<char>('0' + fraction);
  if constexpr (D > 0) *--at = '.';
  (void)digits_before(at, whole);
  return end;
}

char* fixed_by_to_chars(char* out, double value, int decimals) {
  const auto [end, error] =
      std::to_chars(out, out + kCsvNumberMaxChars, value, std::chars_format::fixed, decimals);
  if (error != std::errc{}) throw Error("CSV: cannot format a number");
  return unsigned_zero(out, end);
}

}  // namespace

// In integers, exactly: a finite double is m·2^e, so value·10^d = m·10^d·2^e, and for
// |value| < 2^30 (e ≤ −23) its nearest integer is (m·10^d) >> −e rounded by the bits shifted out
// (m·10^d < 2^83 fits 128 bits). That is the correctly rounded decimal std::to_chars writes;
// exact ties (the bits out are exactly one half), larger values and more than 9 decimals go to
// std::to_chars itself, so the text is always std::to_chars's.
char* write_csv_fixed(char* out, double value, int decimals) {
  if (!std::isfinite(value)) return out;
  if (decimals < 0 || decimals > 9 || !(std::abs(value) < 0x1p30)) {
    return fixed_by_to_chars(out, value, decimals);
  }
  const auto bits = std::bit_cast<std::uint64_t>(value);
  const bool negative = (bits >> 63) != 0;
  const auto biased = static_cast<int>((bits >> 52) & 0x7FF);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  const std::uint64_t m = biased == 0 ? fraction : fraction | (std::uint64_t{1} << 52);
  const int shift = 1075 - (biased == 0 ? 1 : biased);  // −e, ≥ 23 here
  const auto n = static_cast<Uint128>(m) * kPowersOfTen[static_cast<std::size_t>(decimals)];
  std::uint64_t q = 0;
  if (shift < 128) {
    q = static_cast<std::uint64_t>(n >> shift);
    const Uint128 rest = n - (static_cast<Uint128>(q) << shift);
    const Uint128 half = static_cast<Uint128>(1) << (shift - 1);
    if (rest == half) return fixed_by_to_chars(out, value, decimals);  // a tie
    q += static_cast<std::uint64_t>(rest > half);  // no branch: as often up as down
  }            // else value·10^d < 2^83 · 2^−128: rounds to 0
  *out = '-';  // kept only for a non-zero negative value: a zero keeps no sign; no branch
  out += static_cast<std::ptrdiff_t>(negative && q != 0);
  switch (decimals) {
    case 0:
      return scaled_digits<0>(out, q);
    case 1:
      return scaled_digits<1>(out, q);
    case 2:
      return scaled_digits<2>(out, q);
    case 3:
      return scaled_digits<3>(out, q);
    case 4:
      return scaled_digits<4>(out, q);
    case 5:
      return scaled_digits<5>(out, q);
    case 6:
      return scaled_digits<6>(out, q);
    case 7:
      return scaled_digits<7>(out, q);
    case 8:
      return scaled_digits<8>(out, q);
    default:
      return scaled_digits<9>(out, q);
  }
}

char* write_csv_significant(char* out, double value, int digits) {
  if (!std::isfinite(value)) return out;
  const auto [end, error] = std::to_chars(out, out + 64, value, std::chars_format::general, digits);
  if (error != std::errc{}) throw Error("CSV: cannot format a number");
  return unsigned_zero(out, end);
}

char* write_csv_integer(char* out, std::int64_t value) {
  return std::to_chars(out, out + 24, value).ptr;
}

void append_csv_fixed(std::string& out, double value, int decimals) {
  std::array<char, kCsvNumberMaxChars> text{};
  out.append(text.data(), write_csv_fixed(text.data(), value, decimals));
}

void append_csv_significant(std::string& out, double value, int digits) {
  std::array<char, 64> text{};
  out.append(text.data(), write_csv_significant(text.data(), value, digits));
}

void append_csv_integer(std::string& out, std::int64_t value) {
  std::array<char, 24> text{};
  out.append(text.data(), write_csv_integer(text.data(), value));
}

std::string csv_cell(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string cell = "\"";
  for (const char c : text) {
    if (c == '"') cell += '"';
    cell += c;
  }
  cell += '"';
  return cell;
}

void split_csv_cells(std::string_view line, std::vector<std::string_view>& cells) {
  cells.clear();
  std::size_t start = 0;
  for (;;) {
    std::size_t end = start;
    if (end < line.size() && line[end] == '"') {
      for (++end; end < line.size(); ++end) {
        if (line[end] != '"') continue;
        if (end + 1 < line.size() && line[end + 1] == '"') {
          ++end;
        } else {
          ++end;
          break;
        }
      }
    }
    const std::size_t comma = line.find(',', end);
    cells.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) return;
    start = comma + 1;
  }
}

std::string csv_cell_text(std::string_view cell) {
  if (cell.size() < 2 || cell.front() != '"' || cell.back() != '"') return std::string(cell);
  std::string text;
  for (std::size_t i = 1; i + 1 < cell.size(); ++i) {
    text += cell[i];
    if (cell[i] == '"') ++i;  // a doubled quote
  }
  return text;
}

}  // namespace owsim
