#include "io/run/truth_csv.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"

namespace owsim {
namespace {

// A row's characters after its object and class cells, at most: five numbers (kCsvNumberMaxChars
// each, far more than a real value takes), in_view, an integer (24) and the commas.
constexpr std::size_t kRowTailMaxChars = 5 * kCsvNumberMaxChars + 1 + 24 + 16;
// Rows are built in a block on the stack and appended a block at a time: one append per ~100
// rows, not three per row.
constexpr std::size_t kBlockChars = 16384;

}  // namespace

TruthCsvRows::TruthCsvRows(const Scene& scene) {
  const std::size_t count = named_object_count(scene);
  prefix_starts_.reserve(count + 1);
  prefix_starts_.push_back(0);
  for (std::size_t object = 0; object < count; ++object) {
    prefixes_ += csv_cell(named_object_id(scene, object));
    prefixes_ += ',';
    prefixes_ += to_string(named_object_class(scene, object));
    prefixes_ += ',';
    prefix_starts_.push_back(prefixes_.size());
  }
}

void TruthCsvRows::encode(const FrameTruth& truth, std::string& out) const {
  for (const TruthRow& row : truth.rows) {
    if (row.object + std::size_t{1} >= prefix_starts_.size()) {
      throw Error("truth.csv: object index " + std::to_string(row.object) +
                  " is not one of the scene's " + std::to_string(prefix_starts_.size() - 1) +
                  " objects");
    }
  }
  // The frame and time cells are the same on every row: formatted once.
  char head[2 * kCsvNumberMaxChars + 2];
  char* at = write_csv_integer(head, truth.frame);
  *at++ = ',';
  at = write_csv_fixed(at, truth.time_s, 9);
  *at++ = ',';
  const std::string_view frame_cells(head, static_cast<std::size_t>(at - head));
  char block[kBlockChars];
  char* write = block;
  for (const TruthRow& row : truth.rows) {
    const std::size_t first = prefix_starts_[row.object];
    const std::string_view object_cells(prefixes_.data() + first,
                                        prefix_starts_[row.object + 1] - first);
    const std::size_t most = frame_cells.size() + object_cells.size() + kRowTailMaxChars;
    if (static_cast<std::size_t>(block + kBlockChars - write) < most) {
      out.append(block, write);
      write = block;
    }
    if (most <= kBlockChars) {
      write = std::copy(frame_cells.begin(), frame_cells.end(), write);
      write = std::copy(object_cells.begin(), object_cells.end(), write);
    } else {  // an object id longer than a block: its cells go straight out
      out += frame_cells;
      out += object_cells;
    }
    write = write_csv_fixed(write, row.range_m, 3);
    *write++ = ',';
    write = write_csv_fixed(write, row.alpha_deg, 4);
    *write++ = ',';
    write = write_csv_fixed(write, row.beta_deg, 4);
    *write++ = ',';
    *write++ = row.in_view ? '1' : '0';
    *write++ = ',';
    write = write_csv_integer(write, static_cast<std::int64_t>(row.returns));
    *write++ = ',';
    write = write_csv_fixed(write, row.closing_speed_mps, 3);
    *write++ = ',';
    if (row.closing_speed_mps > 0.0) {
      const double time_to_reach_s = row.range_m / row.closing_speed_mps;
      if (std::isfinite(time_to_reach_s)) write = write_csv_fixed(write, time_to_reach_s, 3);
    }
    *write++ = '\n';
  }
  out.append(block, write);
}

TruthCsvWriter::TruthCsvWriter(AtomicOutputFile file, std::uint64_t rows_written)
    : file_(std::move(file)), rows_written_(rows_written) {}

TruthCsvWriter::TruthCsvWriter(std::filesystem::path final_path, AtomicOutputOptions options)
    : TruthCsvWriter(AtomicOutputFile(std::move(final_path), options), 0) {
  std::string header(kTruthCsvHeader);
  header += '\n';
  file_.write(header);
}

TruthCsvWriter TruthCsvWriter::resume(std::filesystem::path final_path,
                                      const WriterCheckpoint& from, AtomicOutputOptions options) {
  return TruthCsvWriter(AtomicOutputFile::resume(std::move(final_path), from.file_bytes, options),
                        from.records);
}

void TruthCsvWriter::append(std::string_view rows, std::uint64_t row_count) {
  file_.write(rows);
  rows_written_ += row_count;
}

WriterCheckpoint TruthCsvWriter::checkpoint() {
  file_.flush();
  return {file_.bytes_written(), rows_written_};
}

void TruthCsvWriter::finish() { file_.commit(); }

}  // namespace owsim
