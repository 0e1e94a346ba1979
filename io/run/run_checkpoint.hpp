#pragma once
// The checkpoint of `owsim run` (`--resume`, INTERFACE.md): a hidden binary file in the output
// folder, `.owsim-resume`, replaced atomically (temporary + rename) while a run goes on. It says
// how many frames are complete and holds everything the outputs had accumulated at that moment:
// each temporary file's size (its bytes all handed to the kernel, so they outlive a SIGKILL), the
// word, row and point counts, the LAS header statistics and creation day, the summary totals and
// the ground truth of the objects seen so far, and the quick-look map. From it a killed run
// continues at its first incomplete frame and finishes with the bytes of an uninterrupted run.
//
// `run` names the run that wrote it: an object of everything that changes output bytes (owsim
// version, contents of the scenario and the files it reads, seed, noise, frame count, outputs) and
// nothing that does not (threads); a resume compares it key by key.
//
// The file: "OWSIMRUN", the format version (u32), an FNV-1a 64 checksum of the body (u64), and
// the body — little-endian fields in a fixed order (io/files/binary_record.hpp): the run as JSON
// text, the frame count, the summary totals, the number of objects tallied and each seen object
// (76 bytes: its index and its ObjectTruth, doubles as their exact bits), then the outputs'
// states, the map mask run-length coded. Its size and the time to write it grow with the objects
// seen, not with the scene: a million unseen trees cost nothing. A checkpoint changed by a single
// byte is refused ("damaged checkpoint"), never resumed into spliced outputs; so is one of
// another format version, such as the JSON `.owsim-resume.json` of owsim before version 3.
// Errors throw owsim::Error naming the file.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "io/files/writer_checkpoint.hpp"
#include "io/images/quicklook.hpp"
#include "io/points/las_writer.hpp"
#include "io/run/flight_summary.hpp"

namespace owsim {

inline constexpr std::string_view kRunCheckpointFileName = ".owsim-resume";
// 3: binary (1, 2: JSON, in .owsim-resume.json); 4: the building and fog classes, returns seen
// through fog; 5: truth.csv; 6: the noise class (false returns)
inline constexpr int kRunCheckpointVersion = 6;
// Where owsim wrote its JSON checkpoints (versions 1 and 2); --resume refuses one left there.
inline constexpr std::string_view kJsonRunCheckpointFileName = ".owsim-resume.json";

struct RunCheckpoint {
  nlohmann::json run = nlohmann::json::object();  // the run that wrote it (see above)
  std::int64_t frames_done = 0;  // frames 0 … frames_done − 1 are in the outputs
  bool finishing = false;        // written by finish(): outputs may be under their final names
  FlightSummaryCheckpoint summary;
  std::optional<WriterCheckpoint> words;  // flight.d64 or flight.hellas
  std::optional<WriterCheckpoint> points_csv;
  std::optional<LasCheckpoint> points_las;
  std::optional<WriterCheckpoint> points_ply;
  std::optional<WriterCheckpoint> trajectory;
  std::optional<WriterCheckpoint> truth;
  std::optional<QuicklookCheckpoint> quicklook;
  friend bool operator==(const RunCheckpoint&, const RunCheckpoint&) = default;
};

// `<directory>/.owsim-resume`
[[nodiscard]] std::filesystem::path run_checkpoint_path(const std::filesystem::path& directory);

// The checkpoint file's bytes around a `body`: the magic, the version, the body's checksum.
[[nodiscard]] std::string checkpoint_file_bytes(std::string_view body);

// Replaces the file at `path` atomically (no fsync: a checkpoint guards against a killed process,
// not a lost machine).
void write_run_checkpoint(const std::filesystem::path& path, const RunCheckpoint& checkpoint);
// std::nullopt if there is no file at `path`. Throws owsim::Error naming the file if it cannot be
// read, is not a checkpoint of this version, or is damaged.
[[nodiscard]] std::optional<RunCheckpoint> read_run_checkpoint(const std::filesystem::path& path);

// Throws owsim::Error naming the checkpoint file and the first key whose value differs between
// the run that wrote it and this one.
void require_same_run(const std::filesystem::path& path, const nlohmann::json& checkpointed,
                      const nlohmann::json& now);

// FNV-1a, 64 bit, over bytes: a fingerprint that changes when the bytes change (not a
// cryptographic hash; it detects edits, not tampering).
class ContentHash {
 public:
  void add(const void* data, std::size_t size);
  // The whole file. Throws owsim::Error naming the path if it cannot be read.
  void add_file(const std::filesystem::path& path);
  [[nodiscard]] std::uint64_t value() const;
  // 16 hex digits.
  [[nodiscard]] std::string hex() const;
  // hex() of `text` alone.
  [[nodiscard]] static std::string hex_of(std::string_view text);

 private:
  std::uint64_t state_ = 0xcbf29ce484222325u;  // the FNV-1a 64-bit offset basis
};

}  // namespace owsim
