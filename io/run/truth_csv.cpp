#include "io/run/truth_csv.hpp"

#include <cmath>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/csv_cells.hpp"

namespace owsim {

TruthCsvRows::TruthCsvRows(const Scene& scene) {
  const std::size_t count = named_object_count(scene);
  object_cells_.reserve(count);
  classes_.reserve(count);
  for (std::size_t object = 0; object < count; ++object) {
    object_cells_.push_back(csv_cell(named_object_id(scene, object)));
    classes_.push_back(named_object_class(scene, object));
  }
}

void TruthCsvRows::encode(const FrameTruth& truth, std::string& out) const {
  for (const TruthRow& row : truth.rows) {
    if (row.object >= object_cells_.size()) {
      throw Error("truth.csv: object index " + std::to_string(row.object) +
                  " is not one of the scene's " + std::to_string(object_cells_.size()) +
                  " objects");
    }
  }
  for (const TruthRow& row : truth.rows) {
    append_csv_integer(out, truth.frame);
    out += ',';
    append_csv_fixed(out, truth.time_s, 9);
    out += ',';
    out += object_cells_[row.object];
    out += ',';
    out += to_string(classes_[row.object]);
    out += ',';
    append_csv_fixed(out, row.range_m, 3);
    out += ',';
    append_csv_fixed(out, row.alpha_deg, 4);
    out += ',';
    append_csv_fixed(out, row.beta_deg, 4);
    out += row.in_view ? ",1," : ",0,";
    append_csv_integer(out, static_cast<std::int64_t>(row.returns));
    out += ',';
    append_csv_fixed(out, row.closing_speed_mps, 3);
    out += ',';
    if (row.closing_speed_mps > 0.0) {
      const double time_to_reach_s = row.range_m / row.closing_speed_mps;
      if (std::isfinite(time_to_reach_s)) append_csv_fixed(out, time_to_reach_s, 3);
    }
    out += '\n';
  }
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
