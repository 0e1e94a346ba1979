#include "io/points/points_csv_writer.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"

namespace owsim {
namespace {

constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

}  // namespace

PointsCsvRows::PointsCsvRows(std::string file, const std::vector<std::string>& object_ids)
    : file_(std::move(file)) {
  object_cells_.reserve(object_ids.size());
  for (const std::string& id : object_ids) {
    object_cells_.push_back(csv_cell(id));
    max_object_cell_ = std::max(max_object_cell_, object_cells_.back().size());
  }
}

void PointsCsvRows::encode(std::span<const PointRecord> points, std::string& rows) const {
  // Rows are written in place: the string grows in steps (zero-filled once), then is cut to
  // what was written.
  const std::size_t start = rows.size();
  std::size_t used = start;
  try {
    for (const PointRecord& point : points) {
      const std::size_t bound = kRowMaxChars + max_object_cell_;
      if (rows.size() - used < bound) {
        rows.resize(std::max(2 * rows.size(), used + bound + kGrowth));
      }
      used = static_cast<std::size_t>(write_row(point, rows.data() + used) - rows.data());
    }
  } catch (...) {
    rows.resize(start);
    throw;
  }
  rows.resize(used);
}

PointsCsvWriter::PointsCsvWriter(AtomicOutputFile file, std::vector<std::string> object_ids,
                                 std::uint64_t points_written)
    : file_(std::move(file)),
      format_(file_.final_path().string(), object_ids),
      points_written_(points_written) {
  buffer_.reserve(kFlushBytes);  // append() never fills it past the flush mark
}

PointsCsvWriter::PointsCsvWriter(std::filesystem::path final_path,
                                 std::vector<std::string> object_ids, AtomicOutputOptions options)
    : PointsCsvWriter(AtomicOutputFile(std::move(final_path), options), std::move(object_ids), 0) {
  buffer_ += kPointsCsvHeader;
  buffer_ += '\n';
}

PointsCsvWriter PointsCsvWriter::resume(std::filesystem::path final_path,
                                        std::vector<std::string> object_ids,
                                        const WriterCheckpoint& from, AtomicOutputOptions options) {
  return PointsCsvWriter(AtomicOutputFile::resume(std::move(final_path), from.file_bytes, options),
                         std::move(object_ids), from.records);
}

WriterCheckpoint PointsCsvWriter::checkpoint() {
  flush_buffer();
  file_.flush();
  return {file_.bytes_written(), points_written_};
}

char* PointsCsvRows::write_row(const PointRecord& point, char* out) const {
  if (point.object_index != kNoObject && point.object_index >= object_cells_.size()) {
    throw input_error(file_, "object index " + std::to_string(point.object_index) +
                                 " is not in the table of " + std::to_string(object_cells_.size()) +
                                 " object ids");
  }
  out = write_csv_integer(out, point.frame);
  *out++ = ',';
  out = write_csv_integer(out, point.pulse);
  *out++ = ',';
  out = write_csv_integer(out, point.line);
  *out++ = ',';
  out = write_csv_integer(out, point.fiber);
  *out++ = ',';
  out = write_csv_integer(out, point.return_number);
  *out++ = ',';
  out = write_csv_fixed(out, point.time_s, 9);
  *out++ = ',';
  out = write_csv_fixed(out, point.range_m, 4);
  *out++ = ',';
  out = write_csv_integer(out, point.counter);
  for (int axis = 0; axis < 3; ++axis) {
    *out++ = ',';
    out = write_csv_fixed(out, point.enu_m[axis], 4);
  }
  *out++ = ',';
  out = write_csv_fixed(out, point.geodetic.lat_deg, 9);
  *out++ = ',';
  out = write_csv_fixed(out, point.geodetic.lon_deg, 9);
  *out++ = ',';
  out = write_csv_fixed(out, point.geodetic.h_m, 4);
  *out++ = ',';
  const std::string_view surface =
      point.surface ? to_string(*point.surface) : std::string_view("unknown");
  out = std::copy(surface.begin(), surface.end(), out);
  *out++ = ',';
  if (point.object_index != kNoObject) {
    const std::string& cell = object_cells_[point.object_index];
    out = std::copy(cell.begin(), cell.end(), out);
  }
  *out++ = ',';
  out = write_csv_significant(out, point.energy_rel, 9);
  *out++ = ',';
  out = write_csv_fixed(out, point.incidence_deg, 4);
  *out++ = '\n';
  return out;
}

void PointsCsvWriter::write(std::span<const PointRecord> points) {
  rows_.clear();
  encode(points, rows_);
  append(rows_, points.size());
}

void PointsCsvWriter::encode(std::span<const PointRecord> points, std::string& rows) const {
  format_.encode(points, rows);
}

void PointsCsvWriter::append(std::string_view rows, std::uint64_t row_count) {
  if (buffer_.size() + rows.size() > kFlushBytes) flush_buffer();
  if (rows.size() >= kFlushBytes) {
    file_.write(rows);
  } else {
    buffer_ += rows;
  }
  points_written_ += row_count;
}

void PointsCsvWriter::skip(std::uint64_t bytes, std::uint64_t row_count) {
  flush_buffer();
  file_.skip(bytes);
  points_written_ += row_count;
}

void PointsCsvWriter::flush_buffer() {
  file_.write(buffer_);
  buffer_.clear();
}

void PointsCsvWriter::finish() {
  flush_buffer();
  file_.commit();
}

}  // namespace owsim
