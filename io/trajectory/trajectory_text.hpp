#pragma once
// Line and field handling shared by the text trajectory readers (io/trajectory/hellsim_reader.hpp,
// io/trajectory/trajectory_csv_reader.hpp, io/trajectory/ardupilot_log_reader.hpp): splitting,
// trimming and strict number parsing, with errors "<path>:<line>: <problem>".
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace owsim {

// Fields separated by runs of spaces or tabs (empty fields never occur).
[[nodiscard]] std::vector<std::string_view> split_whitespace(std::string_view line);
// Fields separated by `separator`, each trimmed of surrounding whitespace (empty fields kept).
[[nodiscard]] std::vector<std::string_view> split_fields(std::string_view line, char separator);
// `text` without leading and trailing whitespace (including a CR left by CRLF line ends).
[[nodiscard]] std::string_view trim(std::string_view text);
// The whole field as a number (a leading '+' allowed), or nullopt; NaN and infinities parse.
[[nodiscard]] std::optional<double> parse_double(std::string_view field);
// The field as a finite number, or throws owsim::Error "<path>:<line>: <column> '<field>' is not
// a finite number".
[[nodiscard]] double finite_field(std::string_view field, const std::string& path, std::size_t line,
                                  std::string_view column);

}  // namespace owsim
