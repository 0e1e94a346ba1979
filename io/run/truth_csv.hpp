#pragma once
// truth.csv (INTERFACE.md "Ground truth and detection evidence", docs/evidence.md): one row per
// frame and scene object within the counter's timeout range of the sensor, columns
//   frame,time_s,object,class,range_m,alpha_deg,beta_deg,in_view,returns,closing_speed_mps,
//   time_to_reach_s
// Fixed decimals, so the bytes do not depend on the host: time_s 9 (the frame's middle, on the
// pulse grid), range_m 3 (1 mm), the angles 4, closing_speed_mps 3, time_to_reach_s 3 (range ÷
// closing speed, empty when the aircraft is not closing). `object` RFC 4180 quoted where needed.
// TruthCsvRows encodes rows on any thread; TruthCsvWriter appends them through an AtomicOutputFile
// (nothing under the final name before finish(); checkpoint() and resume() continue an interrupted
// run's file). Errors throw owsim::Error naming the path.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/scene.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/writer_checkpoint.hpp"
#include "io/run/frame_truth.hpp"

namespace owsim {

inline constexpr std::string_view kTruthCsvHeader =
    "frame,time_s,object,class,range_m,alpha_deg,beta_deg,in_view,returns,closing_speed_mps,"
    "time_to_reach_s";

class TruthCsvRows {
 public:
  // The object and class cells of the scene's named objects.
  explicit TruthCsvRows(const Scene& scene);
  // Appends the rows of `truth` to `out`. Throws owsim::Error for an object index the scene does
  // not name.
  void encode(const FrameTruth& truth, std::string& out) const;

 private:
  // Each named object's "object,class," cells, one after another in one string (a frame's rows
  // read ~500 of them): object k's from prefix_starts_[k] to prefix_starts_[k + 1].
  std::string prefixes_;
  std::vector<std::size_t> prefix_starts_;
};

class TruthCsvWriter {
 public:
  // Writes the header line.
  explicit TruthCsvWriter(std::filesystem::path final_path, AtomicOutputOptions options = {});
  // Continues the temporary an interrupted writer left at `from`. Throws owsim::Error naming the
  // path if it is missing or shorter.
  [[nodiscard]] static TruthCsvWriter resume(std::filesystem::path final_path,
                                             const WriterCheckpoint& from,
                                             AtomicOutputOptions options = {});
  // Appends encoded rows (TruthCsvRows::encode), `row_count` of them.
  void append(std::string_view rows, std::uint64_t row_count);
  // Hands every row written so far to the kernel; where to resume from.
  [[nodiscard]] WriterCheckpoint checkpoint();
  // Flushes and renames the file to its final name.
  void finish();

 private:
  TruthCsvWriter(AtomicOutputFile file, std::uint64_t rows_written);

  AtomicOutputFile file_;
  std::uint64_t rows_written_ = 0;
};

}  // namespace owsim
