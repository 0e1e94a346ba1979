#include "io/report/report_points.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>

#include "geometry/error.hpp"
#include "geometry/scene.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/input_file.hpp"

namespace owsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uintmax_t kMaxPlyHeaderBytes = 65536;
// A vertex of points.ply (io/points/ply_writer.hpp): double x y z, float intensity, uchar class.
constexpr std::size_t kPlyVertexBytes = 3 * 8 + 4 + 1;

// Columns of points.csv the page uses, by their INTERFACE.md names.
enum Column { kFrame, kLine, kFiber, kReturn, kTime, kRange, kE, kN, kU, kClass, kColumnCount };
constexpr std::array<std::string_view, kColumnCount> kColumnNames = {
    "frame", "line", "fiber", "return", "time_s", "range_m", "e_m", "n_m", "u_m", "class"};

// points.ply's class byte (io/points/ply_writer.hpp) as a SurfaceClass code: 0..5 the class's own
// code, 7 noise (INTERFACE.md "PLY class 7"), anything else unknown.
std::uint8_t surface_of_ply(std::uint8_t code) {
  constexpr std::uint8_t kPlyNoise = 7;
  if (code == kPlyNoise) return static_cast<std::uint8_t>(SurfaceClass::noise);
  return code < static_cast<std::uint8_t>(SurfaceClass::noise) ? code : kUnknownSurface;
}

class CsvLineError {
 public:
  CsvLineError(const std::filesystem::path& path, std::uint64_t line)
      : where_(path.string() + ":" + std::to_string(line)) {}
  [[noreturn]] void raise(std::string_view problem) const { throw input_error(where_, problem); }

 private:
  std::string where_;
};

double number_cell(std::string_view cell, Column column, const CsvLineError& at) {
  double value = 0;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (error != std::errc() || end != cell.data() + cell.size()) {
    at.raise(std::string(kColumnNames[column]) + ": '" + std::string(cell) + "' is not a number");
  }
  return value;
}

std::uint8_t surface_cell(std::string_view cell, const CsvLineError& at) {
  if (cell == "unknown" || cell.empty()) return kUnknownSurface;
  const std::optional<SurfaceClass> surface = surface_class_from_string(cell);
  if (!surface) at.raise("class: '" + std::string(cell) + "' is not a class");
  return static_cast<std::uint8_t>(*surface);
}

class PointsCsvParser {
 public:
  PointsCsvParser(std::filesystem::path path, ReportPoints& out)
      : path_(std::move(path)), out_(out) {}

  void line(std::string_view text) {
    ++line_number_;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (line_number_ == 1) return header(without_utf8_bom(text));
    if (text.empty()) return;
    const CsvLineError at(path_, line_number_);
    split_csv_cells(text, cells_);
    if (cells_.size() != header_cells_) {
      at.raise(std::to_string(cells_.size()) + " cells, the header has " +
               std::to_string(header_cells_));
    }
    const auto cell = [&](Column c) { return cells_[static_cast<std::size_t>(index_[c])]; };
    const auto number = [&](Column c) {
      return index_[c] < 0 ? kNaN : number_cell(cell(c), c, at);
    };
    out_.e_m.push_back(static_cast<float>(number(kE)));
    out_.n_m.push_back(static_cast<float>(number(kN)));
    out_.u_m.push_back(static_cast<float>(number(kU)));
    out_.range_m.push_back(static_cast<float>(number(kRange)));
    out_.surface.push_back(index_[kClass] < 0 ? kUnknownSurface : surface_cell(cell(kClass), at));
    if (!out_.pulses_known) return;
    const double frame = number(kFrame);
    if (!(frame >= 0 && frame < static_cast<double>(kMaxReportFrames))) {
      at.raise("frame: outside 0..2e9");
    }
    out_.frame.push_back(static_cast<std::int32_t>(frame));
    out_.line.push_back(static_cast<std::int16_t>(std::clamp(number(kLine), -1.0, 32767.0)));
    out_.fiber.push_back(static_cast<std::int16_t>(std::clamp(number(kFiber), -1.0, 32767.0)));
    out_.return_number.push_back(
        static_cast<std::uint8_t>(std::clamp(number(kReturn), 0.0, 255.0)));
    const double time_s = number(kTime);
    if (std::isfinite(time_s)) {
      const auto [first, added] =
          out_.frame_first_time_s.try_emplace(static_cast<std::int32_t>(frame), time_s);
      if (!added && time_s < first->second) first->second = time_s;
    }
  }

 private:
  void header(std::string_view text) {
    std::vector<std::string_view> names;
    split_csv_cells(text, names);
    header_cells_ = names.size();
    for (std::size_t c = 0; c < kColumnCount; ++c) {
      for (std::size_t i = 0; i < names.size(); ++i) {
        if (names[i] == kColumnNames[c]) index_[c] = static_cast<int>(i);
      }
    }
    for (const Column required : {kE, kN, kU}) {
      if (index_[required] < 0) {
        throw input_error(path_.string() + ":1",
                          "no column " + std::string(kColumnNames[required]) +
                              " (points.csv of owsim run or owsim decode has e_m, n_m, u_m)");
      }
    }
    out_.pulses_known =
        index_[kFrame] >= 0 && index_[kLine] >= 0 && index_[kFiber] >= 0 && index_[kReturn] >= 0;
  }

  std::filesystem::path path_;
  ReportPoints& out_;
  std::uint64_t line_number_ = 0;
  std::size_t header_cells_ = 0;
  std::array<int, kColumnCount> index_ = [] {
    std::array<int, kColumnCount> none{};
    none.fill(-1);
    return none;
  }();
  std::vector<std::string_view> cells_;
};

std::ifstream open_input(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path.string(), "cannot open for reading");
  return in;
}

}  // namespace

void for_each_record(std::istream& in, std::uint64_t count, std::size_t bytes,
                     const std::filesystem::path& path,
                     const std::function<void(const char* record)>& each) {
  constexpr std::uint64_t kBlock = 65536;
  std::vector<char> block(bytes * kBlock);
  for (std::uint64_t done = 0; done < count;) {
    const std::uint64_t n = std::min(kBlock, count - done);
    in.read(block.data(), static_cast<std::streamsize>(n * bytes));
    if (!in) throw input_error(path.string(), "read error");
    for (std::uint64_t i = 0; i < n; ++i) each(block.data() + i * bytes);
    done += n;
  }
}

ReportPoints read_report_points_csv(const std::filesystem::path& path) {
  ReportPoints points;
  points.source = "points.csv";
  PointsCsvParser parser(path, points);
  std::ifstream in = open_input(path);
  std::string buffer;
  std::string carry;
  constexpr std::size_t kChunk = 8u << 20;
  std::vector<char> chunk(kChunk);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(kChunk));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    carry.append(chunk.data(), got);
    std::string_view rest(carry);
    for (std::size_t newline; (newline = rest.find('\n')) != std::string_view::npos;) {
      parser.line(rest.substr(0, newline));
      rest.remove_prefix(newline + 1);
    }
    carry.erase(0, carry.size() - rest.size());
  }
  if (in.bad()) throw file_error(path.string(), "read error");
  if (!carry.empty()) parser.line(carry);
  return points;
}

ReportPoints read_report_points_ply(const std::filesystem::path& path) {
  const auto bad = [&](std::string_view problem) { return input_error(path.string(), problem); };
  const std::uintmax_t size = require_input_file(path, "points file");
  std::ifstream in = open_input(path);
  // The header, within its first 64 KiB: "ply", the format, comments, one vertex element and
  // the layout io/points/ply_writer.hpp writes, nothing else.
  std::string head(static_cast<std::size_t>(std::min<std::uintmax_t>(size, kMaxPlyHeaderBytes)),
                   '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  if (!in) throw file_error(path.string(), "read error");
  constexpr std::string_view kStart = "ply\nformat binary_little_endian 1.0\n";
  constexpr std::string_view kCount = "element vertex ";
  constexpr std::string_view kLayout =
      "property double x\nproperty double y\nproperty double z\nproperty float intensity\n"
      "property uchar class\nend_header\n";
  const std::string_view text(head);
  std::size_t at = text.starts_with(kStart) ? kStart.size() : text.size();
  while (text.substr(at).starts_with("comment ")) {
    const std::size_t newline = text.find('\n', at);
    at = newline == std::string_view::npos ? text.size() : newline + 1;
  }
  const std::size_t count_end = text.find('\n', at);
  std::uint64_t vertices = 0;
  bool have_count = false;
  if (text.substr(at).starts_with(kCount) && count_end != std::string_view::npos) {
    const std::string_view count = text.substr(at + kCount.size(), count_end - at - kCount.size());
    const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), vertices);
    have_count = error == std::errc() && end == count.data() + count.size() && !count.empty();
  }
  if (!have_count || !text.substr(count_end + 1).starts_with(kLayout)) {
    throw bad(
        "not the PLY layout owsim writes (binary little-endian double x y z, float "
        "intensity, uchar class)");
  }
  // The vertices fill the rest of the file exactly: counted from its size, so no product of the
  // header's count can wrap.
  const std::size_t header_bytes = count_end + 1 + kLayout.size();
  const std::uintmax_t body_bytes = size - header_bytes;
  if (body_bytes % kPlyVertexBytes != 0 || body_bytes / kPlyVertexBytes != vertices) {
    throw bad("holds " + std::to_string(body_bytes) + " bytes after its header, which says " +
              std::to_string(vertices) + " vertices of " + std::to_string(kPlyVertexBytes) +
              " bytes");
  }
  ReportPoints points;
  points.source = "points.ply";
  points.e_m.reserve(vertices);
  in.clear();
  in.seekg(static_cast<std::streamoff>(header_bytes));
  for_each_record(in, vertices, kPlyVertexBytes, path, [&](const char* v) {
    std::array<double, 3> xyz{};
    std::memcpy(xyz.data(), v, sizeof xyz);
    points.add(xyz[0], xyz[1], xyz[2], static_cast<float>(kNaN),
               surface_of_ply(static_cast<std::uint8_t>(v[28])));
  });
  return points;
}

}  // namespace owsim
