#pragma once
// The cells of owsim's CSV files (points.csv, trajectory.csv): numbers with a fixed resolution
// and one spelling of zero, so the bytes do not depend on the host, and RFC 4180 text cells; and
// the lines and cells of the CSV files owsim reads.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace owsim {

// The same cells written at `out`, which must have kCsvNumberMaxChars free: each returns the end
// of what it wrote. For rows built in a buffer (points.csv), without a std::string per number.
inline constexpr std::size_t kCsvNumberMaxChars = 352;  // the longest double in fixed notation
[[nodiscard]] char* write_csv_fixed(char* out, double value, int decimals);
[[nodiscard]] char* write_csv_significant(char* out, double value, int digits);
[[nodiscard]] char* write_csv_integer(char* out, std::int64_t value);

// Appends `value` with exactly `decimals`
// decimals ("-0.0000" becomes "0.0000"); a NaN or infinite value appends nothing (empty cell).
void append_csv_fixed(std::string& out, double value, int decimals);
// Appends `value` with `digits` significant digits in %g style; NaN or infinite: nothing.
void append_csv_significant(std::string& out, double value, int digits);
// Appends a decimal integer.
void append_csv_integer(std::string& out, std::int64_t value);
// The cell for `text`: unchanged, or in double quotes with quotes doubled if it holds a comma,
// a double quote, CR or LF (RFC 4180).
[[nodiscard]] std::string csv_cell(std::string_view text);
// `text` without the UTF-8 byte-order mark (EF BB BF) it may start with: spreadsheets write one at
// the start of a CSV file. Every reader of a CSV file takes its first line through this.
[[nodiscard]] constexpr std::string_view without_utf8_bom(std::string_view text) {
  return text.starts_with("\xEF\xBB\xBF") ? text.substr(3) : text;
}
// Calls visit(line, row) for each line of `text` (a byte-order mark at its start dropped): line
// numbers from 1, rows without their "\n" or "\r\n". Text after the last line break is a line too.
template <typename Visit>
void for_each_line(std::string_view text, Visit&& visit) {
  text = without_utf8_bom(text);
  std::size_t begin = 0;
  for (std::int64_t line = 1; begin < text.size(); ++line) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view row = text.substr(begin, end - begin);
    begin = end + 1;
    if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
    visit(line, row);
  }
}

// An RFC 4180 cell as split_csv_cells returns it, as its text: quotes removed, doubled quotes
// made single.
[[nodiscard]] std::string csv_cell_text(std::string_view cell);
// Splits one line (no line break) into `cells` at the commas outside double quotes; a quoted cell
// is returned with its quotes, as written. Reading owsim's own files back (`owsim view`).
void split_csv_cells(std::string_view line, std::vector<std::string_view>& cells);

}  // namespace owsim
