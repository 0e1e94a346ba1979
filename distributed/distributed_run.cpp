#include "distributed/distributed_run.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstring>
#include <exception>
#include <optional>

#include "distributed/placed_frame_bytes.hpp"
#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/little_endian.hpp"
#include "io/images/quicklook.hpp"
#include "io/run/flight_outputs.hpp"

namespace owsim {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRoot = 0;

// The outputs whose bytes every process places: the words, points.csv, points.las, points.ply.
enum Part : std::size_t { kWords, kCsv, kLas, kPly, kParts };
using PartSizes = std::array<std::uint64_t, kParts>;

// What process 0 tells the others before the first frame: where the run starts, which
// temporaries are open and the bytes each holds; or the error that stops every process.
struct Start {
  std::string error;
  std::int64_t first_frame = 0;
  std::array<bool, kParts> open{};
  PartSizes bytes{};
};

std::string start_bytes(const Start& start) {
  if (!start.error.empty()) return "E" + start.error;
  std::string out = "S";
  out.append(reinterpret_cast<const char*>(&start.first_frame), sizeof start.first_frame);
  out.append(reinterpret_cast<const char*>(start.open.data()), sizeof start.open);
  out.append(reinterpret_cast<const char*>(start.bytes.data()), sizeof start.bytes);
  return out;
}

Start read_start(const std::string& bytes) {
  Start start;
  if (bytes.empty() || bytes.front() == 'E') {
    start.error = bytes.empty() ? std::string("no start") : bytes.substr(1);
    return start;
  }
  const char* at = bytes.data() + 1;
  std::memcpy(&start.first_frame, at, sizeof start.first_frame);
  at += sizeof start.first_frame;
  std::memcpy(start.open.data(), at, sizeof start.open);
  at += sizeof start.open;
  std::memcpy(start.bytes.data(), at, sizeof start.bytes);
  return start;
}

template <typename Word>
void append_words(std::span<const Word> words, std::vector<unsigned char>& out) {
  const std::size_t at = out.size();
  out.resize(at + words.size() * sizeof(Word));
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(out.data() + at, words.data(), words.size() * sizeof(Word));
  } else {
    for (std::size_t i = 0; i < words.size(); ++i) {
      store_little_endian(words[i], out.data() + at + i * sizeof(Word));
    }
  }
}

// One process's frames of a round: their bytes by output and what else they add.
struct Block {
  std::array<std::vector<unsigned char>, kParts> bytes;
  std::string placed_frames;

  void clear() {
    for (auto& part : bytes) part.clear();
    placed_frames.clear();
  }

  void add(const FrameEncoding& encoding, const ScanParams& scan, const FrameEncoder& encoder) {
    if (encoding.error) std::rethrow_exception(encoding.error);
    if (encoder.wants(OutputKind::d64)) {
      if (scan.model == SensorModel::milows) {
        append_words<std::uint64_t>(encoding.milows_words, bytes[kWords]);
      } else {
        if (encoding.frame == 0) {
          append_words<std::uint32_t>({&encoding.hellas_header_word, 1}, bytes[kWords]);
        }
        append_words<std::uint32_t>(encoding.hellas_words, bytes[kWords]);
      }
    }
    PlacedFrame placed;
    placed.frame = encoding.frame;
    placed.frame_start = encoding.frame_start;
    placed.tally = encoding.tally;
    if (encoder.wants_points()) placed.points = encoding.points.size();
    if (encoder.wants(OutputKind::csv)) {
      placed.csv_bytes = encoding.csv_rows.size();
      bytes[kCsv].insert(bytes[kCsv].end(), encoding.csv_rows.begin(), encoding.csv_rows.end());
    }
    if (encoder.wants(OutputKind::las)) {
      placed.las.points = encoding.las.points;
      placed.las.points_by_return = encoding.las.points_by_return;
      placed.las.min_record = encoding.las.min_record;
      placed.las.max_record = encoding.las.max_record;
      bytes[kLas].insert(
          bytes[kLas].end(), encoding.las.records.begin(),
          encoding.las.records.begin() +
              static_cast<std::ptrdiff_t>(encoding.las.points * kLasPointRecordBytes));
    }
    if (encoder.wants(OutputKind::truth)) {
      placed.truth_row_count = encoding.truth.rows.size();
      placed.truth_rows = encoding.truth_rows;
    }
    if (encoder.wants(OutputKind::mcap)) encoding.mcap.chunk.append_finished(placed.mcap_chunk);
    if (encoder.wants(OutputKind::ply)) {
      bytes[kPly].insert(bytes[kPly].end(), encoding.ply_vertices.begin(),
                         encoding.ply_vertices.end());
    }
    append_placed_frame(placed, placed_frames);
  }

  [[nodiscard]] PartSizes sizes() const {
    PartSizes sizes{};
    for (std::size_t p = 0; p < kParts; ++p) sizes[p] = bytes[p].size();
    return sizes;
  }
};

// Process 0 opens the outputs (resuming them if asked) and says where the run starts.
Start open_outputs(const FlightSetup& setup, const FlightOutputOptions& output_options,
                   const RunOptions& options, std::optional<FlightOutputs>& outputs) {
  Start start;
  std::optional<RunCheckpoint> checkpoint;
  if (options.resume) checkpoint = checkpoint_to_resume(output_options, setup.frames, options);
  outputs.emplace(output_options, setup.scene, setup.scenario.scan, setup.local_frame,
                  checkpoint ? &*checkpoint : nullptr);
  start.first_frame = outputs->frames_done();
  const FlightOutputs::PlacedFiles files = outputs->placed_files();
  const FlightOutputs::PlacedFile* parts[kParts] = {&files.words, &files.csv, &files.las,
                                                    &files.ply};
  for (std::size_t p = 0; p < kParts; ++p) {
    start.open[p] = !parts[p]->partial_path.empty();
    start.bytes[p] = parts[p]->bytes;
  }
  return start;
}

}  // namespace

RunReport run_distributed(Communicator& comm, const Simulation& simulation,
                          const RunOptions& options, const DistributedRunOptions& distribution) {
  const auto opening = Clock::now();
  const FlightSetup& setup = simulation.setup();
  const ScanParams& scan = setup.scenario.scan;
  const bool root = comm.rank() == kRoot;
  // What every process meets in the options (--resume with mcap) is said once, by process 0.
  FlightOutputOptions output_options;
  try {
    output_options = run_output_options(setup, simulation.run_fingerprint(options), options);
  } catch (const Error& e) {
    if (root) throw JobError(e.what());
    throw ReportedElsewhere();
  }
  output_options.scenario = simulation.scenario_as_flown();

  // Process 0 alone touches the folder's state; a failure there stops every process.
  std::optional<FlightOutputs> outputs;
  std::string start_message;
  if (root) {
    try {
      start_message = start_bytes(open_outputs(setup, output_options, options, outputs));
    } catch (const Error& e) {
      start_message = start_bytes(Start{e.what()});
    }
  }
  comm.broadcast(start_message, kRoot);
  const Start start = read_start(start_message);
  if (!start.error.empty()) {
    if (root) throw JobError(start.error);
    throw ReportedElsewhere();
  }

  // Every process encodes its frames and draws their hits and range images.
  const FrameEncoder encoder(output_options.directory, output_options.outputs, setup.scene, scan,
                             setup.local_frame, output_options.truth);
  std::optional<Quicklook> quicklook;
  if (encoder.wants(OutputKind::quicklook)) {
    QuicklookOptions quicklook_options;
    quicklook_options.every_nth_frame = output_options.quicklook_every_nth_frame;
    quicklook.emplace(output_options.directory / "quicklook", setup.scene, scan,
                      output_options.map_region, quicklook_options);
  }
  const auto merge_map_hits = [&] {
    if (!quicklook) return;
    std::vector<std::uint8_t> mask = quicklook->checkpoint().map_mask;
    comm.or_at_root(mask, kRoot);
    if (root) outputs->add_map_hits(mask);
  };

  const std::filesystem::path names[kParts] = {
      output_options.directory / word_file_name(scan), output_options.directory / "points.csv",
      output_options.directory / "points.las", output_options.directory / "points.ply"};
  std::array<std::unique_ptr<SharedFile>, kParts> files;
  for (std::size_t p = 0; p < kParts; ++p) {
    if (start.open[p]) files[p] = comm.open_shared(AtomicOutputFile::partial_path_for(names[p]));
  }

  const int threads = simulation.threads();
  const std::int64_t frames = setup.frames;
  const std::int64_t per_block = distribution.frames_per_block > 0
                                     ? distribution.frames_per_block
                                     : std::max<std::int64_t>(8, 4 * std::int64_t{threads});
  PartSizes file_bytes = start.bytes;
  Block block;
  const auto began = Clock::now();
  for (std::int64_t next = start.first_frame; next < frames;) {
    const std::int64_t round_frames = std::min(frames - next, per_block * comm.size());
    const std::int64_t mine_first = next + comm.rank() * per_block;
    const std::int64_t mine =
        std::clamp<std::int64_t>(next + round_frames - mine_first, 0, per_block);
    block.clear();
    if (mine > 0) {
      simulation.in_arena([&] {
        encode_frames(
            setup.simulator, setup, FlightRange{mine_first, mine}, threads, encoder,
            [&](const FrameView& frame, const FrameEncoding& encoding) {
              block.add(encoding, scan, encoder);
              if (quicklook) quicklook->add_frame(frame);
            },
            encoder.reads_frame_records() || quicklook ? FrameRecordScope::frame
                                                       : FrameRecordScope::block);
      });
    }
    // Each process's bytes after everything before them: the earlier rounds' and, in this
    // round, the lower ranks' (whose frames come first). Each process's part of an output is one
    // contiguous range of up to megabytes, so each writes its own (MPI_File_write_at): collective
    // buffering would only shuffle the bytes between processes first.
    comm.sleeping_barrier();  // wait for the slowest process without taking a core from others
    const PartSizes sizes = block.sizes();
    const std::vector<std::uint64_t> offsets = comm.exclusive_sum(sizes);
    PartSizes totals = sizes;
    comm.sum(totals);
    for (std::size_t p = 0; p < kParts; ++p) {
      if (!files[p]) continue;
      files[p]->write_at(file_bytes[p] + offsets[p], block.bytes[p]);
      file_bytes[p] += totals[p];
    }
    const std::vector<std::string> placed = comm.gather(block.placed_frames, kRoot);
    if (root) {
      for (const std::string& part : placed) {
        for (const PlacedFrame& frame : read_placed_frames(part)) outputs->add_placed_frame(frame);
      }
    }
    next += round_frames;

    std::string due = root && outputs->checkpoint_due() ? "1" : "0";
    comm.broadcast(due, kRoot);
    if (due == "1") {
      for (const auto& file : files) {
        if (file) file->sync();
      }
      merge_map_hits();
      if (root) outputs->write_checkpoint();
    }
    if (root && options.progress) {
      options.progress(RunProgress{next, frames, start.first_frame,
                                   std::chrono::duration<double>(Clock::now() - began).count()});
    }
  }
  for (const auto& file : files) {
    if (file) file->close();
  }
  merge_map_hits();
  const double wall_s = std::chrono::duration<double>(Clock::now() - began).count();
  RunReport report =
      run_report(setup, output_options.directory, start.first_frame, wall_s, threads, comm.size());
  report.setup_s = simulation.build_s() + std::chrono::duration<double>(began - opening).count();
  if (root) {
    outputs->finish(run_facts(setup.scenario, report));
    if (options.outputs.contains(OutputKind::detections)) {
      write_run_detections(setup, output_options.scenario, output_options.directory);
    }
  }
  comm.barrier();  // every process returns once the files are complete under their names
  return report;
}

}  // namespace owsim
