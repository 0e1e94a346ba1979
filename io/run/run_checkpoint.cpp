#include "io/run/run_checkpoint.hpp"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

#include "geometry/error.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/input_file.hpp"
#include "io/files/json_text.hpp"

namespace owsim {
namespace {

using nlohmann::json;

constexpr std::string_view kFormat = "owsim run checkpoint";
constexpr std::string_view kChecksumPrefix = "owsim run checkpoint fnv1a64 ";
constexpr std::string_view kBase64 =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// ---- the quick-look map mask: runs of equal bytes (value, LEB128 length), in base64 ----

std::vector<std::uint8_t> run_length_coded(const std::vector<std::uint8_t>& bytes) {
  std::vector<std::uint8_t> code;
  for (std::size_t i = 0; i < bytes.size();) {
    std::size_t end = i + 1;
    while (end < bytes.size() && bytes[end] == bytes[i]) ++end;
    code.push_back(bytes[i]);
    for (std::uint64_t run = end - i; run != 0; run >>= 7) {
      code.push_back(static_cast<std::uint8_t>((run & 0x7Fu) | (run > 0x7Fu ? 0x80u : 0u)));
    }
    i = end;
  }
  return code;
}

std::vector<std::uint8_t> run_length_decoded(const std::vector<std::uint8_t>& code,
                                             std::size_t size) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(size);
  for (std::size_t i = 0; i < code.size();) {
    const std::uint8_t value = code[i++];
    std::uint64_t run = 0;
    for (int shift = 0;; shift += 7) {
      if (i == code.size() || shift > 56) throw Error("a run length is cut off");
      const std::uint8_t part = code[i++];
      run |= std::uint64_t{part & 0x7Fu} << shift;
      if ((part & 0x80u) == 0) break;
    }
    if (run == 0 || run > size - bytes.size()) throw Error("the runs overflow the map");
    bytes.insert(bytes.end(), static_cast<std::size_t>(run), value);
  }
  if (bytes.size() != size) throw Error("the runs do not fill the map");
  return bytes;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = bytes.size() - i;
    const std::uint32_t group = std::uint32_t{bytes[i]} << 16 |
                                (left > 1 ? std::uint32_t{bytes[i + 1]} << 8 : 0u) |
                                (left > 2 ? std::uint32_t{bytes[i + 2]} : 0u);
    text += kBase64[(group >> 18) & 63u];
    text += kBase64[(group >> 12) & 63u];
    text += left > 1 ? kBase64[(group >> 6) & 63u] : '=';
    text += left > 2 ? kBase64[group & 63u] : '=';
  }
  return text;
}

std::vector<std::uint8_t> from_base64(std::string_view text) {
  if (text.size() % 4 != 0) throw Error("base64 text of a length that is no multiple of 4");
  std::vector<std::uint8_t> bytes;
  bytes.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    std::uint32_t group = 0;
    int padding = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      std::uint32_t sextet = 0;
      if (c == '=' && i + 4 == text.size() && k >= 2) {
        ++padding;
      } else {
        const std::size_t at = kBase64.find(c);
        if (at == std::string_view::npos || padding > 0) throw Error("not base64 text");
        sextet = static_cast<std::uint32_t>(at);
      }
      group = group << 6 | sextet;
    }
    bytes.push_back(static_cast<std::uint8_t>(group >> 16));
    if (padding < 2) bytes.push_back(static_cast<std::uint8_t>(group >> 8));
    if (padding < 1) bytes.push_back(static_cast<std::uint8_t>(group));
  }
  return bytes;
}

// ---- values ----

json optional_number(const std::optional<double>& value) {
  return value ? json(*value) : json(nullptr);
}

std::optional<double> optional_number_of(const json& value) {
  if (value.is_null()) return std::nullopt;
  return value.get<double>();
}

SurfaceClass surface_of(const std::string& name) {
  for (const SurfaceClass surface :
       {SurfaceClass::wire, SurfaceClass::pole, SurfaceClass::tree, SurfaceClass::ground}) {
    if (name == to_string(surface)) return surface;
  }
  throw Error("unknown class '" + name + "'");
}

json writer_json(const WriterCheckpoint& writer) {
  return {{"bytes", writer.file_bytes}, {"records", writer.records}};
}

WriterCheckpoint writer_of(const json& value) {
  return {value.at("bytes").get<std::uint64_t>(), value.at("records").get<std::uint64_t>()};
}

json summary_json(const FlightSummaryCheckpoint& summary) {
  json objects = json::array();
  for (const ObjectTruth& truth : summary.objects) {
    objects.push_back({{"id", truth.id},
                       {"class", std::string(to_string(truth.surface))},
                       {"returns", truth.returns},
                       {"frames_seen", truth.frames_seen},
                       {"first_seen_s", optional_number(truth.first_seen_s)},
                       {"first_seen_range_m", optional_number(truth.first_seen_range_m)},
                       {"min_range_m", optional_number(truth.min_range_m)},
                       {"last_frame_seen", truth.last_frame_seen}});
  }
  const FlightCounts& counts = summary.counts;
  return {{"frames", counts.frames},
          {"pulses", counts.pulses},
          {"returns_by_class", counts.returns_by_class},
          {"second_returns", counts.second_returns},
          {"objects", objects}};
}

FlightSummaryCheckpoint summary_of(const json& value) {
  FlightSummaryCheckpoint summary;
  summary.counts.frames = value.at("frames").get<std::uint64_t>();
  summary.counts.pulses = value.at("pulses").get<std::uint64_t>();
  summary.counts.returns_by_class =
      value.at("returns_by_class").get<std::array<std::uint64_t, 4>>();
  summary.counts.second_returns = value.at("second_returns").get<std::uint64_t>();
  for (const json& object : value.at("objects")) {
    ObjectTruth& truth = summary.objects.emplace_back();
    truth.id = object.at("id").get<std::string>();
    truth.surface = surface_of(object.at("class").get<std::string>());
    truth.returns = object.at("returns").get<std::uint64_t>();
    truth.frames_seen = object.at("frames_seen").get<std::uint64_t>();
    truth.first_seen_s = optional_number_of(object.at("first_seen_s"));
    truth.first_seen_range_m = optional_number_of(object.at("first_seen_range_m"));
    truth.min_range_m = optional_number_of(object.at("min_range_m"));
    truth.last_frame_seen = object.at("last_frame_seen").get<std::int64_t>();
  }
  return summary;
}

json las_json(const LasCheckpoint& las) {
  json value = writer_json(las.file);
  value["points_by_return"] = las.points_by_return;
  value["min_record"] = las.min_record;
  value["max_record"] = las.max_record;
  value["creation_day_of_year"] = las.creation_date.day_of_year;
  value["creation_year"] = las.creation_date.year;
  return value;
}

LasCheckpoint las_of(const json& value) {
  LasCheckpoint las;
  las.file = writer_of(value);
  las.points_by_return = value.at("points_by_return").get<std::array<std::uint64_t, 15>>();
  las.min_record = value.at("min_record").get<std::array<std::int32_t, 3>>();
  las.max_record = value.at("max_record").get<std::array<std::int32_t, 3>>();
  las.creation_date.day_of_year = value.at("creation_day_of_year").get<int>();
  las.creation_date.year = value.at("creation_year").get<int>();
  return las;
}

json quicklook_json(const QuicklookCheckpoint& quicklook) {
  json last = nullptr;
  if (quicklook.last_trajectory_px) {
    last = {quicklook.last_trajectory_px->x(), quicklook.last_trajectory_px->y()};
  }
  return {{"map_mask_bytes", quicklook.map_mask.size()},
          {"map_mask_runs_base64", base64(run_length_coded(quicklook.map_mask))},
          {"last_trajectory_px", last}};
}

QuicklookCheckpoint quicklook_of(const json& value) {
  QuicklookCheckpoint quicklook;
  quicklook.map_mask =
      run_length_decoded(from_base64(value.at("map_mask_runs_base64").get<std::string>()),
                         value.at("map_mask_bytes").get<std::size_t>());
  const json& last = value.at("last_trajectory_px");
  if (!last.is_null()) {
    const auto px = last.get<std::array<double, 2>>();
    quicklook.last_trajectory_px = Eigen::Vector2d(px[0], px[1]);
  }
  return quicklook;
}

template <typename State, typename ToJson>
void put_optional(json& out, const char* key, const std::optional<State>& state, ToJson to_json) {
  if (state) out[key] = to_json(*state);
}

template <typename State, typename FromJson>
std::optional<State> optional_of(const json& in, const char* key, FromJson from_json) {
  if (!in.contains(key)) return std::nullopt;
  return from_json(in.at(key));
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
  json out = {{"format", kFormat},
              {"version", kRunCheckpointVersion},
              {"run", checkpoint.run},
              {"frames_done", checkpoint.frames_done},
              {"finishing", checkpoint.finishing},
              {"summary", summary_json(checkpoint.summary)}};
  put_optional(out, "words", checkpoint.words, writer_json);
  put_optional(out, "points_csv", checkpoint.points_csv, writer_json);
  put_optional(out, "points_las", checkpoint.points_las, las_json);
  put_optional(out, "points_ply", checkpoint.points_ply, writer_json);
  put_optional(out, "trajectory", checkpoint.trajectory, writer_json);
  put_optional(out, "quicklook", checkpoint.quicklook, quicklook_json);
  // The first line holds a checksum of everything after it, so a checkpoint changed by hand or
  // by a damaged disk is refused, not resumed into spliced outputs.
  AtomicOutputFile file(path, {.sync_on_commit = false});
  file.write(checksummed_checkpoint_text(json_text(out, 1) + "\n"));
  file.commit();
}

std::string checksummed_checkpoint_text(std::string_view body) {
  ContentHash hash;
  hash.add(body.data(), body.size());
  return std::string(kChecksumPrefix) + hash.hex() + "\n" + std::string(body);
}

std::optional<RunCheckpoint> read_run_checkpoint(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return std::nullopt;
  const std::string text = read_input_file(path, "run checkpoint", kMaxCheckpointBytes);
  try {
    const std::size_t line_end = text.find('\n');
    if (!text.starts_with(kChecksumPrefix) || line_end == std::string::npos) {
      throw Error("no checksum line");
    }
    const std::string_view body = std::string_view(text).substr(line_end + 1);
    ContentHash hash;
    hash.add(body.data(), body.size());
    if (text.substr(kChecksumPrefix.size(), line_end - kChecksumPrefix.size()) != hash.hex()) {
      throw Error("its checksum does not match its content");
    }
    const json in = json::parse(body);
    if (in.at("format") != kFormat || in.at("version") != kRunCheckpointVersion) {
      throw Error("not a version " + std::to_string(kRunCheckpointVersion) +
                  " checkpoint of this owsim");
    }
    RunCheckpoint checkpoint;
    checkpoint.run = in.at("run");
    if (!checkpoint.run.is_object()) throw Error("'run' is not an object");
    checkpoint.frames_done = in.at("frames_done").get<std::int64_t>();
    if (checkpoint.frames_done < 0) throw Error("negative frames_done");
    checkpoint.finishing = in.at("finishing").get<bool>();
    checkpoint.summary = summary_of(in.at("summary"));
    checkpoint.words = optional_of<WriterCheckpoint>(in, "words", writer_of);
    checkpoint.points_csv = optional_of<WriterCheckpoint>(in, "points_csv", writer_of);
    checkpoint.points_las = optional_of<LasCheckpoint>(in, "points_las", las_of);
    checkpoint.points_ply = optional_of<WriterCheckpoint>(in, "points_ply", writer_of);
    checkpoint.trajectory = optional_of<WriterCheckpoint>(in, "trajectory", writer_of);
    checkpoint.quicklook = optional_of<QuicklookCheckpoint>(in, "quicklook", quicklook_of);
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

std::string ContentHash::hex() const {
  std::array<char, 17> text{};
  std::snprintf(text.data(), text.size(), "%016llx", static_cast<unsigned long long>(state_));
  return text.data();
}

}  // namespace owsim
