#include "io/points/points_csv_writer.hpp"

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
  for (const std::string& id : object_ids) object_cells_.push_back(csv_cell(id));
}

void PointsCsvRows::encode(std::span<const PointRecord> points, std::string& rows) const {
  for (const PointRecord& point : points) append_row(point, rows);
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

void PointsCsvRows::append_row(const PointRecord& point, std::string& out) const {
  if (point.object_index != kNoObject && point.object_index >= object_cells_.size()) {
    throw input_error(file_,
                      "object index " + std::to_string(point.object_index) +
                          " is not in the table of " + std::to_string(object_cells_.size()) +
                          " object ids");
  }
  append_csv_integer(out, point.frame);
  out += ',';
  append_csv_integer(out, point.pulse);
  out += ',';
  append_csv_integer(out, point.line);
  out += ',';
  append_csv_integer(out, point.fiber);
  out += ',';
  append_csv_integer(out, point.return_number);
  out += ',';
  append_csv_fixed(out, point.time_s, 9);
  out += ',';
  append_csv_fixed(out, point.range_m, 4);
  out += ',';
  append_csv_integer(out, point.counter);
  for (int axis = 0; axis < 3; ++axis) {
    out += ',';
    append_csv_fixed(out, point.enu_m[axis], 4);
  }
  out += ',';
  append_csv_fixed(out, point.geodetic.lat_deg, 9);
  out += ',';
  append_csv_fixed(out, point.geodetic.lon_deg, 9);
  out += ',';
  append_csv_fixed(out, point.geodetic.h_m, 4);
  out += ',';
  out += point.surface ? to_string(*point.surface) : std::string_view("unknown");
  out += ',';
  if (point.object_index != kNoObject) out += object_cells_[point.object_index];
  out += ',';
  append_csv_significant(out, point.energy_rel, 9);
  out += ',';
  append_csv_fixed(out, point.incidence_deg, 4);
  out += '\n';
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
