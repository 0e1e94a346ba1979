#include "io/scenario/esri_ascii_grid.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <string_view>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::optional<double> parse_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::string lower(std::string_view text) {
  std::string result(text);
  std::transform(result.begin(), result.end(), result.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return result;
}

std::string quoted(std::string_view token) {
  std::string text = "'";
  text.append(token);
  text += '\'';
  return text;
}

bool starts_with_letter(std::string_view token) {
  return !token.empty() && std::isalpha(static_cast<unsigned char>(token.front()));
}

class GridReader {
 public:
  explicit GridReader(const std::string& path) : path_(path) {}

  HeightGrid read() {
    file_bytes_ = require_input_file(path_, "terrain grid file", kMaxTerrainGridBytes);
    std::ifstream file(path_);
    if (!file) throw file_error(path_, "cannot open the terrain grid file");
    std::string line;
    bool in_header = true;
    while (std::getline(file, line)) {
      ++line_number_;
      const std::vector<std::string_view> tokens = split_whitespace(line);
      if (tokens.empty()) continue;
      if (in_header && starts_with_letter(tokens.front())) {
        read_header_line(tokens);
        continue;
      }
      if (in_header) {
        in_header = false;
        finish_header();
      }
      for (std::string_view token : tokens) read_value(token);
    }
    if (in_header) finish_header();  // a header with no data: reports the missing keys
    const std::size_t expected = expected_count();
    if (grid_.heights.size() < expected) {
      fail("holds " + std::to_string(grid_.heights.size()) + " values, " +
           std::to_string(grid_.ncols) + " columns × " + std::to_string(grid_.nrows) +
           " rows need " + std::to_string(expected));
    }
    return grid_;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw input_error(path_ + ":" + std::to_string(line_number_), problem);
  }

  void read_header_line(const std::vector<std::string_view>& tokens) {
    const std::string name = lower(tokens.front());
    static const char* const kKnown[] = {"ncols",     "nrows",     "xllcorner", "xllcenter",
                                         "yllcorner", "yllcenter", "cellsize",  "nodata_value"};
    if (std::find(std::begin(kKnown), std::end(kKnown), name) == std::end(kKnown)) {
      fail("unknown header key " + quoted(tokens.front()));
    }
    if (tokens.size() != 2) fail("header key " + name + " needs exactly one value");
    if (header_.count(name) != 0) fail("header key " + name + " is given twice");
    const std::optional<double> value = parse_number(tokens[1]);
    if (!value) fail("the value " + quoted(tokens[1]) + " of " + name + " is not a number");
    header_[name] = *value;
  }

  double require(const char* name) const {
    const auto found = header_.find(name);
    if (found == header_.end()) fail(std::string("missing header key ") + name);
    return found->second;
  }

  int require_count(const char* name) const {
    const double value = require(name);
    if (!(value >= 2.0 && value <= 1e9 && value == std::floor(value))) {
      fail(std::string(name) + " must be an integer ≥ 2");
    }
    return static_cast<int>(value);
  }

  // The lower-left sample centre from either the corner or the centre key of one axis.
  double origin(const char* corner, const char* centre, double cellsize) const {
    const bool has_corner = header_.count(corner) != 0, has_centre = header_.count(centre) != 0;
    if (has_corner == has_centre) {
      fail(std::string(has_corner ? "both " : "missing header key ") + corner + " or " + centre);
    }
    return has_corner ? header_.at(corner) + 0.5 * cellsize : header_.at(centre);
  }

  void finish_header() {
    grid_.ncols = require_count("ncols");
    grid_.nrows = require_count("nrows");
    grid_.cellsize_m = require("cellsize");
    if (!(grid_.cellsize_m > 0.0)) fail("cellsize must be > 0");
    grid_.x_west_m = origin("xllcorner", "xllcenter", grid_.cellsize_m);
    grid_.y_south_m = origin("yllcorner", "yllcenter", grid_.cellsize_m);
    if (const auto found = header_.find("nodata_value"); found != header_.end()) {
      grid_.nodata = found->second;
    }
    // Each value takes at least two bytes (a digit and a separator): a header that claims more
    // cells than the file can hold is refused before anything is reserved for them.
    if (expected_count() > file_bytes_ / 2 + 1) {
      fail("the header's " + std::to_string(grid_.ncols) + " columns × " +
           std::to_string(grid_.nrows) + " rows cannot fit in the file's " +
           std::to_string(file_bytes_) + " bytes");
    }
    grid_.heights.reserve(expected_count());
  }

  std::size_t expected_count() const {
    return static_cast<std::size_t>(grid_.ncols) * static_cast<std::size_t>(grid_.nrows);
  }

  void read_value(std::string_view token) {
    const std::optional<double> value = parse_number(token);
    if (!value) fail(quoted(token) + " is not a finite number");
    if (grid_.heights.size() == expected_count()) {
      fail("more values than " + std::to_string(grid_.ncols) + " columns × " +
           std::to_string(grid_.nrows) + " rows");
    }
    grid_.heights.push_back(*value);
  }

  std::string path_;
  std::uintmax_t file_bytes_ = 0;
  int line_number_ = 0;
  std::map<std::string, double> header_;
  HeightGrid grid_;
};

}  // namespace

HeightGrid read_esri_ascii_grid(const std::string& path) { return GridReader(path).read(); }

}  // namespace owsim
