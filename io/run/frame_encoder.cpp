#include "io/run/frame_encoder.hpp"

#include <exception>
#include <string>

#include "geometry/error.hpp"
#include "geometry/utm.hpp"
#include "io/points/frame_points.hpp"
#include "io/points/ply_writer.hpp"
#include "io/recording/frame_words.hpp"

namespace owsim {

FrameEncoder::FrameEncoder(const std::filesystem::path& directory,
                           const std::set<OutputKind>& outputs, const Scene& scene,
                           const ScanParams& scan, const LocalFrame& local_frame,
                           const FrameTruthSource* truth)
    : outputs_(outputs),
      scan_(scan),
      geodesy_(local_frame, outputs.contains(OutputKind::las)
                                ? std::optional(utm_grid_of(local_frame.origin()))
                                : std::nullopt),
      object_count_(named_object_count(scene)),
      truth_(truth) {
  if (truth_ == nullptr) outputs_.erase(OutputKind::truth);
  if (wants(OutputKind::truth)) truth_rows_.emplace(scene);
  if (wants(OutputKind::csv)) csv_.emplace((directory / "points.csv").string(), object_ids(scene));
  if (wants(OutputKind::las)) {
    LasWriterOptions las;
    las.origin = local_frame.origin();
    las_.emplace((directory / "points.las").string(), las);
  }
  if (wants(OutputKind::mcap)) mcap_.emplace(scan, local_frame);
}

void FrameEncoder::size_encoding(FrameEncoding& out) const {
  if (wants(OutputKind::d64)) {
    const auto pulses = static_cast<std::size_t>(scan_.pulses_per_frame());
    if (scan_.model == SensorModel::milows) {
      out.milows_words.resize(pulses);
    } else {
      out.hellas_words.resize(pulses);
    }
  }
  out.line_blocks.resize(static_cast<std::size_t>(scan_.lines_per_frame));
}

void FrameEncoder::encode_pulses(const FrameView& block, int begin, FrameEncoding& out) const {
  const int pulses = scan_.pulses_per_frame();
  const int fibers = scan_.fibers_per_line;
  const bool words = wants(OutputKind::d64);
  const std::size_t word_count =
      scan_.model == SensorModel::milows ? out.milows_words.size() : out.hellas_words.size();
  const auto count = static_cast<std::int64_t>(block.pulses.size());
  const std::int64_t end = std::int64_t{begin} + count;
  if (begin < 0 || count == 0 || end > pulses || begin % fibers != 0 ||
      (end % fibers != 0 && end != pulses) || block.returns.size() != block.pulses.size() ||
      (!block.object_returns.empty() && block.object_returns.size() != block.pulses.size()) ||
      out.line_blocks.size() != static_cast<std::size_t>(scan_.lines_per_frame) ||
      (words && word_count != static_cast<std::size_t>(pulses))) {
    throw Error("outputs: pulses " + std::to_string(begin) + ".." + std::to_string(end) +
                " are not whole lines of a frame of this scan, or the encoding is not sized");
  }
  // The block's tally and error go to the entry of its first line; its other lines' are emptied.
  const auto first_line = static_cast<int>(begin / fibers);
  const auto end_line = static_cast<int>((end + fibers - 1) / fibers);
  for (int line = first_line + 1; line < end_line; ++line) {
    FrameEncoding::LineBlock& empty = out.line_blocks[static_cast<std::size_t>(line)];
    FlightSummary::tally(object_count_, {}, {}, empty.tally);
    empty.error = nullptr;
  }
  FrameEncoding::LineBlock& entry = out.line_blocks[static_cast<std::size_t>(first_line)];
  entry.error = nullptr;
  try {
    // The tally feeds summary.json and truth.csv: without them, the block's tally stays empty.
    const std::size_t tallied =
        wants(OutputKind::summary) || wants(OutputKind::truth) ? block.pulses.size() : 0;
    FlightSummary::tally(
        object_count_, block.pulses.first(tallied), block.returns.first(tallied), entry.tally,
        wants(OutputKind::summary) ? TallyScope::summary : TallyScope::object_hits,
        block.object_returns.empty() ? block.object_returns : block.object_returns.first(tallied));
    if (words) {
      const auto first = static_cast<std::size_t>(begin);
      if (scan_.model == SensorModel::milows) {
        pack_milows_frame(
            block.pulses, block.returns,
            std::span<std::uint64_t>(out.milows_words).subspan(first, block.pulses.size()));
      } else {
        pack_hellas_frame(
            scan_, block.sweep, block.pulses, block.returns,
            std::span<std::uint32_t>(out.hellas_words).subspan(first, block.pulses.size()));
        // What the word file takes once: the HELLAS header word, before the first frame (set
        // for every frame, from its first pulse).
        if (begin == 0) {
          out.hellas_header_word =
              hellas_file_header_word(block.sweep, block.pulses.front().time_s);
        }
      }
    }
  } catch (...) {
    entry.error = std::current_exception();
  }
}

void FrameEncoder::finish_encoding(const FrameView& frame, const Pose& frame_start,
                                   FrameEncoding& out) const {
  out.frame = frame.frame;
  out.frame_start = frame_start;
  out.error = nullptr;
  // The blocks' parts in line order: the first error, and the tally as one pass would give it.
  FlightSummary::tally(object_count_, {}, {}, out.tally);
  for (const FrameEncoding::LineBlock& block : out.line_blocks) {
    if (block.error && !out.error) out.error = block.error;
    out.tally.append(block.tally);
  }
  if (out.error) return;
  try {
    if (makes_points()) {
      // flight.mcap alone takes the East-North-Up positions only: no geodesy.
      frame_points(frame, geodesy_, out.points, recorded_returns(scan_.model), wants_points());
      out.csv_rows.clear();
      if (csv_) csv_->encode(out.points, out.csv_rows);
      if (las_) las_->encode(out.points, out.las);
      if (wants(OutputKind::ply)) PlyWriter::encode(out.points, out.ply_vertices);
      if (mcap_) mcap_->encode(frame.frame, frame_start, out.points, out.mcap);
    }
    out.truth_rows.clear();
    if (truth_rows_) {
      truth_->frame_truth(frame.frame, frame.sweep, out.tally.object_hits, out.truth);
      truth_rows_->encode(out.truth, out.truth_rows);
    }
  } catch (...) {
    out.error = std::current_exception();
  }
}

void FrameEncoder::encode_frame(const FrameView& frame, const Pose& frame_start,
                                FrameEncoding& out) const {
  size_encoding(out);
  encode_pulses(frame, 0, out);
  finish_encoding(frame, frame_start, out);
}

}  // namespace owsim
