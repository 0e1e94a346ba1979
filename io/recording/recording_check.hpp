#pragma once
// What a MilOWS (.d64) or HELLAS (.hellas) recording holds, and whether its structure is sound
// (SENSOR-SPEC §1, §2, §8; INTERFACE.md `owsim info`).
//
// The file is streamed word by word (io/recording/word_file.hpp), never loaded whole. The report
// counts frames, lines, pulses and returns, summarises the counters, unwraps the time tags and
// gives the encoder range; it lists **problems** — what breaks the sensor's frame/line structure or
// cannot come from the sensor — and **notes** — what is legitimate but worth knowing. Each names
// the 0-based word index in the file (the HELLAS header is word 0).
//
// Problems: trailing bytes of an incomplete word; an empty file; a frame whose length between
// frame gates ≠ pulses_per_frame; a line whose length between line gates ≠ fibers_per_line; a
// frame gate without a line gate; a time-tag step between consecutive pulses other than
// 0..ceil(tick·PRF⁻¹) ticks modulo the wrap; a counter above the timeout; MilOWS: the encoder
// reversing within a frame; HELLAS: a first word that is not a header, a header anywhere else,
// MovDir changing within a frame, a complete frame without exactly one NI.
// Notes: a partial first frame (the recording starts mid-frame) or last frame (it stops
// mid-frame), MilOWS crosstalk / reserved / LUT / trigger bits set, HELLAS Ain not toggling at
// the line gates as owsim writes it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sensor/motor_encoder.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/sensor_model.hpp"

namespace owsim {

enum class RecordingIssueKind {
  // problems
  trailing_bytes,
  empty_file,
  frame_length,
  line_length,
  frame_gate_without_line_gate,
  time_tag_jump,
  counter_beyond_timeout,
  encoder_reversal,
  missing_header,
  extra_header,
  mov_dir_change,
  ni_count,
  // notes
  partial_frame,
  crosstalk_flag,
  reserved_bit,
  lut_bits,
  trigger_bits,
  ain_pattern,
};

[[nodiscard]] std::string_view to_string(RecordingIssueKind kind);

struct RecordingIssue {
  std::uint64_t word = 0;  // 0-based word index in the file
  RecordingIssueKind kind = RecordingIssueKind::frame_length;
  std::string description;  // one line
};

// Distribution of one counter over the pulses. Valid counts are those below the timeout;
// quartiles are nearest-rank (the smallest count with at least p·valid counts at or below it).
struct CounterSummary {
  std::uint64_t valid = 0;           // returns: counter < timeout
  std::uint64_t timeouts = 0;        // counter == timeout: no return
  std::uint64_t beyond_timeout = 0;  // counter > timeout: cannot come from the sensor
  std::uint16_t min = 0, q1 = 0, median = 0, q3 = 0, max = 0;  // of the valid counts, 0 if none
};

struct TimeTagSummary {
  double tick_s = 0.0;          // MilOWS 100 µs, HELLAS 0.5 ms
  std::uint32_t modulus = 0;    // MilOWS 65536, HELLAS 16384
  std::uint16_t first_tag = 0;  // of the first pulse
  std::uint16_t last_tag = 0;   // of the last pulse
  std::uint64_t wraps = 0;      // times the tag ran past its modulus
  std::int64_t span_ticks = 0;  // last − first, unwrapped
  double span_s = 0.0;          // span_ticks · tick_s
  double pulses_span_s = 0.0;   // (pulses − 1) / PRF: what the span should be
};

struct EncoderSummary {  // MilOWS
  EncoderCount min_counts = 0, max_counts = 0;
  double mirror_beta_min_deg = 0.0, mirror_beta_max_deg = 0.0;  // via the §3 polynomial
};

struct HellasHeaderSummary {
  std::uint16_t beta_code = 0;   // bits 0–11 of the header word
  double mirror_beta_deg = 0.0;  // code · 0.01° − 20.48°
};

struct RecordingReport {
  std::filesystem::path path;
  SensorModel model = SensorModel::milows;
  int fibers_per_line = 0;
  int pulses_per_frame = 0;
  std::uint16_t timeout_counts = 0;

  std::uint64_t file_bytes = 0;
  std::size_t word_bytes = 0;
  std::uint64_t words = 0;         // whole words
  std::size_t trailing_bytes = 0;  // bytes of an incomplete last word
  std::uint64_t header_words = 0;  // HELLAS Select = 1 words (not pulses)
  std::uint64_t pulses = 0;
  std::uint64_t complete_frames = 0;  // pulses_per_frame pulses between two frame gates
  std::uint64_t lines = 0;            // lines ended by a line gate, without a partial first one
  std::uint64_t leading_partial_pulses =
      0;  // before the first frame start (recording began mid-frame)
  std::uint64_t trailing_partial_pulses =
      0;  // after the last frame gate (recording stopped mid-frame)

  // Index fiber − 1 (slot within the line counted from the last line gate); the reference fiber is
  // the last entry. Pulses in a line longer than fibers_per_line belong to no fiber.
  std::vector<std::uint64_t> returns_per_fiber;  // counter 1 (HELLAS: the counter) < timeout
  std::vector<std::uint64_t>
      second_returns_per_fiber;      // MilOWS counter 2 < timeout; empty for HELLAS
  std::uint64_t returns = 0;         // all first returns, any slot
  std::uint64_t second_returns = 0;  // all second returns, any slot

  CounterSummary counter1;                 // optical fibers (every slot but the reference)
  std::optional<CounterSummary> counter2;  // MilOWS only, optical fibers
  CounterSummary reference_counter;        // counter 1 of the reference fiber
  TimeTagSummary time;
  std::optional<EncoderSummary> encoder;      // MilOWS, when it has pulses
  std::optional<HellasHeaderSummary> header;  // HELLAS, when word 0 is a header
  std::uint64_t ni_marks = 0;                 // HELLAS

  std::vector<RecordingIssue> problems;  // the first max_listed in word order
  std::uint64_t problem_count = 0;       // all of them
  std::vector<RecordingIssue> notes;
  std::uint64_t note_count = 0;
  std::map<std::string, std::uint64_t> problem_counts;  // by kind name

  [[nodiscard]] bool sound() const { return problem_count == 0; }
};

struct RecordingCheckOptions {
  std::size_t max_listed = 20;  // problems (and notes) listed in full; the rest only counted
};

// The model a file name stands for: .d64 → MilOWS, .hellas → HELLAS (case-insensitive).
[[nodiscard]] std::optional<SensorModel> recording_model_from_extension(
    const std::filesystem::path& path);
// "d64" → MilOWS, "hellas" → HELLAS (the `--format` values of `owsim info`).
[[nodiscard]] std::optional<SensorModel> parse_recording_format(std::string_view text);
// "d64" or "hellas".
[[nodiscard]] std::string_view recording_format_name(SensorModel model);

// Reads the file as `scan.model` words and checks it against `scan` (fibers per line, lines per
// frame, counter timeout, PRF). Throws owsim::Error naming the path if it cannot be read.
[[nodiscard]] RecordingReport check_recording(const std::filesystem::path& path,
                                              const ScanParams& scan,
                                              const RecordingCheckOptions& options = {});

// The report for people (several lines, ending in a newline) and for programs (`--json`).
[[nodiscard]] std::string render_text(const RecordingReport& report);
[[nodiscard]] nlohmann::json to_json(const RecordingReport& report);

}  // namespace owsim
