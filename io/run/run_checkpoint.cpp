#include "io/run/run_checkpoint.hpp"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/binary_record.hpp"
#include "io/files/input_file.hpp"
#include "io/files/json_text.hpp"

namespace owsim {
namespace {

using nlohmann::json;

constexpr std::string_view kMagic = "OWSIMRUN";  // then the version, the checksum and the body
constexpr std::size_t kHeaderBytes = kMagic.size() + 4 + 8;
constexpr std::size_t kSeenObjectBytes = 4 + 8 + 8 + 8 + 8 + 8 + 8 + 8 + 8 + 8;
constexpr std::size_t kLargestMapMask = std::size_t{1} << 28;

// Which of a checkpoint's optional states follow, one bit each.
enum StateBit : std::uint8_t {
  kWords = 1u << 0,
  kPointsCsv = 1u << 1,
  kPointsLas = 1u << 2,
  kPointsPly = 1u << 3,
  kTrajectory = 1u << 4,
  kQuicklook = 1u << 5,
  kTruth = 1u << 6,
};

// ---- the quick-look map mask: runs of equal bytes (value, LEB128 length) ----

std::string run_length_coded(const std::vector<std::uint8_t>& bytes) {
  std::string code;
  for (std::size_t i = 0; i < bytes.size();) {
    std::size_t end = i + 1;
    while (end < bytes.size() && bytes[end] == bytes[i]) ++end;
    code.push_back(static_cast<char>(bytes[i]));
    for (std::uint64_t run = end - i; run != 0; run >>= 7) {
      code.push_back(static_cast<char>((run & 0x7Fu) | (run > 0x7Fu ? 0x80u : 0u)));
    }
    i = end;
  }
  return code;
}

std::vector<std::uint8_t> run_length_decoded(std::string_view code, std::size_t size) {
  if (size > kLargestMapMask) throw Error("a map larger than any quick-look map");
  std::vector<std::uint8_t> bytes;
  bytes.reserve(size);
  for (std::size_t i = 0; i < code.size();) {
    const auto value = static_cast<std::uint8_t>(code[i++]);
    std::uint64_t run = 0;
    for (int shift = 0;; shift += 7) {
      if (i == code.size() || shift > 56) throw Error("a run length is cut off");
      const auto part = static_cast<std::uint8_t>(code[i++]);
      run |= std::uint64_t{part & 0x7Fu} << shift;
      if ((part & 0x80u) == 0) break;
    }
    if (run == 0 || run > size - bytes.size()) throw Error("the runs overflow the map");
    bytes.insert(bytes.end(), static_cast<std::size_t>(run), value);
  }
  if (bytes.size() != size) throw Error("the runs do not fill the map");
  return bytes;
}

// ---- the states, in the order of the file ----

void put_writer(BinaryRecordWriter& out, const WriterCheckpoint& writer) {
  out.put(writer.file_bytes);
  out.put(writer.records);
}

WriterCheckpoint writer_of(BinaryRecordReader& in) {
  WriterCheckpoint writer;
  writer.file_bytes = in.get<std::uint64_t>();
  writer.records = in.get<std::uint64_t>();
  return writer;
}

void put_summary(BinaryRecordWriter& out, const FlightSummaryCheckpoint& summary) {
  const FlightCounts& counts = summary.counts;
  out.put(counts.frames);
  out.put(counts.pulses);
  for (const std::uint64_t returns : counts.returns_by_class) out.put(returns);
  out.put(counts.second_returns);
  out.put(summary.object_count);
  out.put(static_cast<std::uint64_t>(summary.seen.size()));
  for (const SeenObject& seen : summary.seen) {
    out.put(seen.index);
    out.put(seen.truth.returns);
    out.put(seen.truth.frames_seen);
    out.put(seen.truth.first_seen_s);
    out.put(seen.truth.first_seen_range_m);
    out.put(seen.truth.min_range_m);
    out.put(seen.truth.last_frame_seen);
    out.put(seen.truth.seen_through_fog);
    out.put(seen.truth.first_seen_clear_s);
    out.put(seen.truth.first_seen_clear_range_m);
  }
}

FlightSummaryCheckpoint summary_of(BinaryRecordReader& in) {
  FlightSummaryCheckpoint summary;
  FlightCounts& counts = summary.counts;
  counts.frames = in.get<std::uint64_t>();
  counts.pulses = in.get<std::uint64_t>();
  for (std::uint64_t& returns : counts.returns_by_class) returns = in.get<std::uint64_t>();
  counts.second_returns = in.get<std::uint64_t>();
  summary.object_count = in.get<std::uint64_t>();
  const auto seen = in.get<std::uint64_t>();
  if (seen > in.left() / kSeenObjectBytes) throw Error("more seen objects than the file holds");
  summary.seen.resize(static_cast<std::size_t>(seen));
  for (SeenObject& object : summary.seen) {
    object.index = in.get<std::uint32_t>();
    object.truth.returns = in.get<std::uint64_t>();
    object.truth.frames_seen = in.get<std::uint64_t>();
    object.truth.first_seen_s = in.get_double();
    object.truth.first_seen_range_m = in.get_double();
    object.truth.min_range_m = in.get_double();
    object.truth.last_frame_seen = in.get<std::int64_t>();
    object.truth.seen_through_fog = in.get<std::uint64_t>();
    object.truth.first_seen_clear_s = in.get_double();
    object.truth.first_seen_clear_range_m = in.get_double();
  }
  return summary;
}

void put_las(BinaryRecordWriter& out, const LasCheckpoint& las) {
  put_writer(out, las.file);
  for (const std::uint64_t points : las.points_by_return) out.put(points);
  for (const std::int32_t value : las.min_record) out.put(value);
  for (const std::int32_t value : las.max_record) out.put(value);
  out.put(static_cast<std::int32_t>(las.creation_date.day_of_year));
  out.put(static_cast<std::int32_t>(las.creation_date.year));
}

LasCheckpoint las_of(BinaryRecordReader& in) {
  LasCheckpoint las;
  las.file = writer_of(in);
  for (std::uint64_t& points : las.points_by_return) points = in.get<std::uint64_t>();
  for (std::int32_t& value : las.min_record) value = in.get<std::int32_t>();
  for (std::int32_t& value : las.max_record) value = in.get<std::int32_t>();
  las.creation_date.day_of_year = in.get<std::int32_t>();
  las.creation_date.year = in.get<std::int32_t>();
  return las;
}

void put_quicklook(BinaryRecordWriter& out, const QuicklookCheckpoint& quicklook) {
  out.put(static_cast<std::uint64_t>(quicklook.map_mask.size()));
  out.put_bytes(run_length_coded(quicklook.map_mask));
  out.put(static_cast<std::uint8_t>(quicklook.last_trajectory_px ? 1 : 0));
  if (quicklook.last_trajectory_px) {
    out.put(quicklook.last_trajectory_px->x());
    out.put(quicklook.last_trajectory_px->y());
  }
}

QuicklookCheckpoint quicklook_of(BinaryRecordReader& in) {
  QuicklookCheckpoint quicklook;
  const auto size = in.get<std::uint64_t>();
  quicklook.map_mask = run_length_decoded(in.get_bytes(), static_cast<std::size_t>(size));
  if (in.get<std::uint8_t>() != 0) {
    const double x = in.get_double();
    const double y = in.get_double();
    quicklook.last_trajectory_px = Eigen::Vector2d(x, y);
  }
  return quicklook;
}

std::string shown(const json& value) {
  constexpr std::size_t kLongest = 40;
  std::string text = json_text(value);
  if (text.size() > kLongest) text = text.substr(0, kLongest) + "…";
  return text;
}

}  // namespace

std::filesystem::path run_checkpoint_path(const std::filesystem::path& directory) {
  return directory / kRunCheckpointFileName;
}

void write_run_checkpoint(const std::filesystem::path& path, const RunCheckpoint& checkpoint) {
  BinaryRecordWriter out;
  out.put_bytes(json_text(checkpoint.run));
  out.put(checkpoint.frames_done);
  out.put(static_cast<std::uint8_t>(checkpoint.finishing ? 1 : 0));
  put_summary(out, checkpoint.summary);
  const auto bit = [](bool present, StateBit state) {
    return present ? static_cast<unsigned>(state) : 0u;
  };
  out.put(static_cast<std::uint8_t>(bit(checkpoint.words.has_value(), kWords) |
                                    bit(checkpoint.points_csv.has_value(), kPointsCsv) |
                                    bit(checkpoint.points_las.has_value(), kPointsLas) |
                                    bit(checkpoint.points_ply.has_value(), kPointsPly) |
                                    bit(checkpoint.trajectory.has_value(), kTrajectory) |
                                    bit(checkpoint.quicklook.has_value(), kQuicklook) |
                                    bit(checkpoint.truth.has_value(), kTruth)));
  if (checkpoint.words) put_writer(out, *checkpoint.words);
  if (checkpoint.points_csv) put_writer(out, *checkpoint.points_csv);
  if (checkpoint.points_las) put_las(out, *checkpoint.points_las);
  if (checkpoint.points_ply) put_writer(out, *checkpoint.points_ply);
  if (checkpoint.trajectory) put_writer(out, *checkpoint.trajectory);
  if (checkpoint.quicklook) put_quicklook(out, *checkpoint.quicklook);
  if (checkpoint.truth) put_writer(out, *checkpoint.truth);
  AtomicOutputFile file(path, {.sync_on_commit = false});
  file.write(checkpoint_file_bytes(out.bytes()));
  file.commit();
}

std::string checkpoint_file_bytes(std::string_view body) {
  ContentHash hash;
  hash.add(body.data(), body.size());
  BinaryRecordWriter header;
  header.put(static_cast<std::uint32_t>(kRunCheckpointVersion));
  header.put(hash.value());
  std::string bytes(kMagic);
  bytes += header.bytes();
  bytes += body;
  return bytes;
}

std::optional<RunCheckpoint> read_run_checkpoint(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return std::nullopt;
  const std::string bytes = read_input_file(path, "run checkpoint", kMaxCheckpointBytes);
  try {
    if (bytes.size() < kHeaderBytes || !bytes.starts_with(kMagic)) {
      throw Error("not an owsim run checkpoint");
    }
    BinaryRecordReader header(std::string_view(bytes).substr(kMagic.size(), 12));
    if (header.get<std::uint32_t>() != kRunCheckpointVersion) {
      throw Error("not a version " + std::to_string(kRunCheckpointVersion) +
                  " checkpoint of this owsim");
    }
    const std::string_view body = std::string_view(bytes).substr(kHeaderBytes);
    ContentHash hash;
    hash.add(body.data(), body.size());
    if (header.get<std::uint64_t>() != hash.value()) {
      throw Error("its checksum does not match its content");
    }
    BinaryRecordReader in(body);
    RunCheckpoint checkpoint;
    checkpoint.run = json::parse(in.get_bytes());
    if (!checkpoint.run.is_object()) throw Error("'run' is not an object");
    checkpoint.frames_done = in.get<std::int64_t>();
    if (checkpoint.frames_done < 0) throw Error("negative frames_done");
    checkpoint.finishing = in.get<std::uint8_t>() != 0;
    checkpoint.summary = summary_of(in);
    const auto states = in.get<std::uint8_t>();
    if ((states & kWords) != 0) checkpoint.words = writer_of(in);
    if ((states & kPointsCsv) != 0) checkpoint.points_csv = writer_of(in);
    if ((states & kPointsLas) != 0) checkpoint.points_las = las_of(in);
    if ((states & kPointsPly) != 0) checkpoint.points_ply = writer_of(in);
    if ((states & kTrajectory) != 0) checkpoint.trajectory = writer_of(in);
    if ((states & kQuicklook) != 0) checkpoint.quicklook = quicklook_of(in);
    if ((states & kTruth) != 0) checkpoint.truth = writer_of(in);
    if (in.left() != 0) throw Error("bytes after the last state");
    return checkpoint;
  } catch (const std::exception& e) {  // nlohmann::json's errors and ours
    throw input_error(path.string(), std::string("damaged checkpoint (") + e.what() +
                                         "); run without --resume to start over");
  }
}

void require_same_run(const std::filesystem::path& path, const json& checkpointed,
                      const json& now) {
  for (const auto& [key, value] : now.items()) {
    const json was = checkpointed.contains(key) ? checkpointed.at(key) : json(nullptr);
    if (was != value) {
      throw input_error(path.string(), "written by a different run: " + key + " was " + shown(was) +
                                           ", now " + shown(value) +
                                           " (run without --resume to start over)");
    }
  }
  for (const auto& [key, value] : checkpointed.items()) {
    if (!now.contains(key)) {
      throw input_error(path.string(), "written by a different run: it has " + key + " " +
                                           shown(value) + " (run without --resume to start over)");
    }
  }
}

void ContentHash::add(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    state_ ^= bytes[i];
    state_ *= 0x100000001b3u;  // the FNV 64-bit prime
  }
}

void ContentHash::add_file(const std::filesystem::path& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    throw file_error(path.string(), std::string("cannot open: ") + std::strerror(errno));
  }
  std::vector<unsigned char> buffer(std::size_t{1} << 16);
  std::size_t got = 0;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) add(buffer.data(), got);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw input_error(path.string(), "read error");
}

std::string ContentHash::hex_of(std::string_view text) {
  ContentHash hash;
  hash.add(text.data(), text.size());
  return hash.hex();
}

std::uint64_t ContentHash::value() const { return state_; }

std::string ContentHash::hex() const {
  std::array<char, 17> text{};
  std::snprintf(text.data(), text.size(), "%016llx", static_cast<unsigned long long>(state_));
  return text.data();
}

}  // namespace owsim
