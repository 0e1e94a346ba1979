#include "io/files/csv_cells.hpp"

#include <array>
#include <charconv>
#include <cmath>

#include "geometry/error.hpp"

namespace owsim {
namespace {

// Drops the sign of a formatted zero ("-0.0000" → "0.0000") so the output has one spelling.
void append_unsigned_zero(std::string& out, const char* first, const char* last) {
  if (*first == '-') {
    bool zero = true;
    for (const char* c = first + 1; c != last; ++c) {
      if (*c != '0' && *c != '.') {
        zero = false;
        break;
      }
    }
    if (zero) ++first;
  }
  out.append(first, last);
}

}  // namespace

void append_csv_fixed(std::string& out, double value, int decimals) {
  if (!std::isfinite(value)) return;
  std::array<char, 352> text{};  // the longest double in fixed notation is ~330 characters
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value,
                                          std::chars_format::fixed, decimals);
  if (error != std::errc{}) throw Error("CSV: cannot format a number");
  append_unsigned_zero(out, text.data(), end);
}

void append_csv_significant(std::string& out, double value, int digits) {
  if (!std::isfinite(value)) return;
  std::array<char, 64> text{};
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value,
                                          std::chars_format::general, digits);
  if (error != std::errc{}) throw Error("CSV: cannot format a number");
  append_unsigned_zero(out, text.data(), end);
}

void append_csv_integer(std::string& out, std::int64_t value) {
  std::array<char, 24> text{};
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value);
  out.append(text.data(), end);
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

}  // namespace owsim
