#pragma once
// points.csv: one row per detected return (INTERFACE.md "`owsim run` outputs"), columns
//   frame,pulse,line,fiber,return,time_s,range_m,counter,e_m,n_m,u_m,lat_deg,lon_deg,h_m,class,
//   object,energy_rel,incidence_deg
// Fixed decimals, so a row holds the values to a stated resolution and the bytes do not depend on
// the host: time_s 9 (1 ns); range_m, e_m, n_m, u_m, h_m 4 (0.1 mm); lat_deg, lon_deg 9 (≤ 0.11 mm
// on the ground); incidence_deg 4; energy_rel 9 significant digits (%g style, so a tiny energy
// keeps its digits: 1.23456789e-05). A value that rounds to zero is written unsigned ("0.0000").
// `class` is wire|pole|tree|ground, or `unknown` for a return without a class (decoded words);
// `object` is the record's entry of the object-id table (RFC 4180 quoted if it holds a comma,
// quote or line break), empty for kNoObject; energy_rel and incidence_deg are empty when NaN.
// Lines end with "\n". Rows go through a 1 MiB buffer into an AtomicOutputFile: nothing appears
// under the final name before finish(); checkpoint() and resume() let an interrupted run continue
// the file. Errors throw owsim::Error naming the path.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/files/atomic_output_file.hpp"
#include "io/files/csv_cells.hpp"
#include "io/files/writer_checkpoint.hpp"
#include "io/points/point_record.hpp"

namespace owsim {

inline constexpr std::string_view kPointsCsvHeader =
    "frame,pulse,line,fiber,return,time_s,range_m,counter,e_m,n_m,u_m,lat_deg,lon_deg,h_m,class,"
    "object,energy_rel,incidence_deg";

// The rows points.csv holds for points, without a file: what PointsCsvWriter::encode writes, for
// encoders that run where no writer is (the other processes of a distributed run).
class PointsCsvRows {
 public:
  // object_ids[i] is the `object` cell of a record with object_index i; `file` names the file in
  // errors.
  PointsCsvRows(std::string file, const std::vector<std::string>& object_ids);
  // Appends the rows of `points` to `rows`. Throws owsim::Error if a record's object_index is
  // neither kNoObject nor in the table (`rows` is then as it was).
  void encode(std::span<const PointRecord> points, std::string& rows) const;

 private:
  // A row's characters besides the object cell, at most: 5 integers and a counter (24 each),
  // 10 numbers (kCsvNumberMaxChars each, far more than any real value takes), class, commas.
  static constexpr std::size_t kRowMaxChars = 6 * 24 + 10 * kCsvNumberMaxChars + 64;
  static constexpr std::size_t kGrowth = std::size_t{1} << 18;  // rows grow 256 KiB at least
  // Writes the row of `point` at `out`, which has kRowMaxChars + max_object_cell_ free.
  [[nodiscard]] char* write_row(const PointRecord& point, char* out) const;

  std::string file_;
  std::vector<std::string> object_cells_;  // the ids, already CSV-quoted where needed
  std::size_t max_object_cell_ = 0;
};

class PointsCsvWriter final : public PointSink {
 public:
  // object_ids[i] is the `object` cell of a record with object_index i. Writes the header line.
  PointsCsvWriter(std::filesystem::path final_path, std::vector<std::string> object_ids,
                  AtomicOutputOptions options = {});
  // Continues the temporary file an interrupted writer left at `from` (bytes after it are cut
  // off). Throws owsim::Error naming the path if the temporary is missing or shorter.
  [[nodiscard]] static PointsCsvWriter resume(std::filesystem::path final_path,
                                              std::vector<std::string> object_ids,
                                              const WriterCheckpoint& from,
                                              AtomicOutputOptions options = {});

  // Throws owsim::Error if a record's object_index is neither kNoObject nor in the table.
  void write(std::span<const PointRecord> points) override;
  // write() in two steps, so the formatting can run on other threads: encode() appends the rows
  // of `points` to `rows` (reads only what the constructor set, so it may run concurrently with
  // itself and with append(); throws as write()), append() writes `row_count` encoded rows.
  void encode(std::span<const PointRecord> points, std::string& rows) const;
  void append(std::string_view rows, std::uint64_t row_count);
  // Counts `row_count` rows of `bytes` bytes as written that another process put into the
  // temporary after the ones written so far (a distributed run).
  void skip(std::uint64_t bytes, std::uint64_t row_count);
  void finish() override;
  [[nodiscard]] std::uint64_t points_written() const override { return points_written_; }
  // Hands every row written so far to the kernel; where to resume from.
  [[nodiscard]] WriterCheckpoint checkpoint();

 private:
  PointsCsvWriter(AtomicOutputFile file, std::vector<std::string> object_ids,
                  std::uint64_t points_written);
  void flush_buffer();

  AtomicOutputFile file_;
  PointsCsvRows format_;
  std::string buffer_;
  std::string rows_;  // write()'s encoded rows, reused
  std::uint64_t points_written_ = 0;
};

}  // namespace owsim
