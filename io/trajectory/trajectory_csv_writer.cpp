#include "io/trajectory/trajectory_csv_writer.hpp"

#include <utility>

#include "io/files/csv_cells.hpp"

namespace owsim {
namespace {

constexpr std::size_t kFlushBytes = std::size_t{1} << 16;
constexpr std::size_t kRowBytesMax = 512;  // a row of finite values

}  // namespace

TrajectoryCsvWriter::TrajectoryCsvWriter(AtomicOutputFile file, const LocalFrame& frame,
                                         std::uint64_t rows_written)
    : file_(std::move(file)), frame_(frame), rows_written_(rows_written) {
  buffer_.reserve(kFlushBytes + kRowBytesMax);
}

TrajectoryCsvWriter::TrajectoryCsvWriter(std::filesystem::path final_path, const LocalFrame& frame,
                                         AtomicOutputOptions options)
    : TrajectoryCsvWriter(AtomicOutputFile(std::move(final_path), options), frame, 0) {
  buffer_ += kTrajectoryCsvHeader;
  buffer_ += '\n';
}

TrajectoryCsvWriter TrajectoryCsvWriter::resume(std::filesystem::path final_path,
                                                const LocalFrame& frame,
                                                const WriterCheckpoint& from,
                                                AtomicOutputOptions options) {
  return TrajectoryCsvWriter(
      AtomicOutputFile::resume(std::move(final_path), from.file_bytes, options), frame,
      from.records);
}

WriterCheckpoint TrajectoryCsvWriter::checkpoint() {
  flush_buffer();
  file_.flush();
  return {file_.bytes_written(), rows_written_};
}

void TrajectoryCsvWriter::write(const Pose& pose) {
  const Geodetic geodetic = frame_.geodetic_from_enu(pose.position_enu_m);
  std::string& out = buffer_;
  append_csv_fixed(out, pose.time_s, 9);
  out += ',';
  append_csv_fixed(out, geodetic.lat_deg, 9);
  out += ',';
  append_csv_fixed(out, geodetic.lon_deg, 9);
  out += ',';
  append_csv_fixed(out, geodetic.h_m, 4);
  for (int axis = 0; axis < 3; ++axis) {
    out += ',';
    append_csv_fixed(out, pose.position_enu_m[axis], 4);
  }
  out += ',';
  append_csv_fixed(out, pose.attitude.roll_deg, 9);
  out += ',';
  append_csv_fixed(out, pose.attitude.pitch_deg, 9);
  out += ',';
  append_csv_fixed(out, pose.attitude.heading_deg, 9);
  out += '\n';
  ++rows_written_;
  if (buffer_.size() >= kFlushBytes) flush_buffer();
}

void TrajectoryCsvWriter::write(std::span<const Pose> poses) {
  for (const Pose& pose : poses) write(pose);
}

void TrajectoryCsvWriter::flush_buffer() {
  file_.write(buffer_);
  buffer_.clear();
}

void TrajectoryCsvWriter::finish() {
  flush_buffer();
  file_.commit();
}

}  // namespace owsim
