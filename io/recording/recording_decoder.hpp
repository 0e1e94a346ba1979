#pragma once
// A MilOWS (.d64) or HELLAS (.hellas) recording read back into pulses (SENSOR-SPEC §2, §3, §8;
// source ch. 2, 8, 10): for every word, its frame and pulse index, time, fiber, α, the mirror β
// and the ray's β, and its counters — what a replay tool needs before it places a point.
//
// Structure. io/recording/recording_check.hpp walks the frame and line gates first (the same report
// as `owsim info`); a recording it finds unsound is refused (a frame or line of the wrong length, a
// frame gate without a line gate, a time-tag jump, HELLAS header/MovDir/NI faults), since its
// pulses cannot be numbered; so is a file whose size is not a whole number of words (cut inside
// a word, or not a word file at all). A recording may start mid-frame (even mid-line) and stop
// mid-frame: the first frame gate numbers the pulses before it, so pulse i of the file is global
// pulse n = n0 + i, frame ⌊n / pulses_per_frame⌋, pulse n mod pulses_per_frame.
//
// Time. The time tags (MilOWS 100 µs, HELLAS 0.5 ms, cyclic) are unwrapped and t0 + i/PRF is fitted
// to them: every tag u_i says u_i·tick ≤ t0 + i/PRF < (u_i + 1)·tick, and t0 is the middle of the
// window all of them leave (a few µs wide after a few hundred pulses; if the tags disagree with
// the PRF the window is empty and t0 is the minimax compromise, the misfit reported). The tags
// fix t0 only modulo their wrap (6.5536 s MilOWS, 8.192 s HELLAS): the decoder takes the t0
// nearest the start hint, or without one the first t0 from the scenario's start_s on (1 ms of
// slack before it) — a recording cut from a longer flight needs the hint. Then, if the global pulse
// index n0 = round((t0 − start_s)·PRF) lands within 1 µs of the window and agrees with the
// structure (n0 mod pulses_per_frame = the first pulse's index), the recording lies on the
// scenario's pulse grid — as every owsim recording does — and each pulse's time is exactly the
// simulator's start_s + n/PRF (sensor/scan_pattern.hpp pulse_time_s, bit for bit). Otherwise the
// fitted t0 + i/PRF is used (error below one pulse period, 16 µs) and frames are numbered from
// the nearest grid frame. A recording without any frame gate can only be placed on the grid.
//
// β. MilOWS: the mirror β from the motor encoder through the inverse §3 polynomial (quantised to
// 0.0055° of motor angle, i.e. within ±0.0018° of the simulated mirror β), plus β_FC by fiber.
// HELLAS: (k − k_NI)·MAF with the sign of MovDir (eq 4.3, within MAF/2 = 0.0009°), plus β_FC. A
// HELLAS frame without its NI mark (a partial first or last frame) takes its β from the file's
// header word (the first frame: ±0.005°) or else from the nominal sweep start ∓18° (off by up to
// the frame jitter, 0.114°); which source each frame used is reported.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/recording/recording_check.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

// How a recording's pulse times were rebuilt.
enum class RecordingTiming {
  scenario_grid,  // exactly start_s + n/PRF: the tags agree with the scenario's pulse grid
  fitted,         // t0 + i/PRF with t0 fitted to the tags
};

// Where a frame's mirror β came from.
enum class MirrorBetaSource {
  encoder,  // MilOWS motor encoder, every pulse
  ni_mark,  // HELLAS: the frame's NI mark
  header,   // HELLAS: the file's header word (first frame without its NI mark)
  nominal,  // HELLAS: the nominal sweep start (a frame without NI mark or header)
};

[[nodiscard]] std::string_view to_string(RecordingTiming timing);
[[nodiscard]] std::string_view to_string(MirrorBetaSource source);

struct RecordingDecoderOptions {
  // Roughly when the first pulse fired, on the trajectory's clock; picks the tag wrap nearest it.
  // nullopt: the first wrap from the scenario's start_s (ScanParams::start_s) on.
  std::optional<double> start_hint_s;
};

// What the decoder found in a recording before decoding it: the structure check, where the
// pulses sit on the scenario's frame grid, and how their times were rebuilt.
struct RecordingLayout {
  RecordingReport check;  // io/recording/recording_check.hpp, sound (the decoder refuses otherwise)
  std::uint64_t pulses = 0;
  std::optional<std::uint32_t> hellas_header_word;  // HELLAS word 0 as read, when it is a header
  std::optional<std::uint16_t> hellas_header_code;  // its β code (bits 0–11)
  std::uint64_t first_pulse_word = 0;               // file index of the first pulse (HELLAS: 1)

  std::int64_t first_global_pulse = 0;  // n0 = frame · pulses_per_frame + pulse of the first pulse
  std::int64_t first_frame = 0;         // frame index of the first pulse
  int first_pulse_in_frame = 0;         // its index within that frame
  std::int64_t last_frame = 0;          // frame index of the last pulse
  int last_pulse_in_frame = 0;
  std::uint64_t frames = 0;  // frames touched, partial ones included

  RecordingTiming timing = RecordingTiming::fitted;
  double first_pulse_time_s = 0.0;
  double last_pulse_time_s = 0.0;
  double tag_window_s = 0.0;  // width of the window the time tags leave for t0 (0 if empty)
  double tag_misfit_s = 0.0;  // 0 when every tag agrees with t0 + i/PRF, else the disagreement
  std::uint64_t time_tag_wraps = 0;

  // The time of pulse `pulse` of `frame` (SENSOR-SPEC §2 pinned timing on the grid, else fitted).
  [[nodiscard]] double pulse_time_s(const ScanParams& scan, std::int64_t frame, int pulse) const;
};

// One frame of a recording: the consecutive pulses first_pulse.. of `frame` that the file holds
// (all of them but in a partial first or last frame).
struct DecodedFrame {
  std::int64_t frame = 0;
  // direction (from MovDir, or the encoder's trend), mirror β of pulse 0 as decoded, time of
  // pulse 0; centre_shift_deg is not decoded (0).
  FrameSweep sweep;
  MirrorBetaSource beta_source = MirrorBetaSource::encoder;
  int ni_pulse = -1;             // HELLAS: the pulse index carrying the NI mark; −1 if none
  std::uint64_t first_word = 0;  // file index of pulses[0]'s word
  // index, line, slot, fiber, reference, time, α (NaN on the reference fiber), mirror β, the
  // ray's β, encoder (MilOWS), gates and MovDir as the words say.
  std::vector<Pulse> pulses;
  std::vector<std::uint64_t> words;  // the words as read (HELLAS: 32-bit values)
  std::vector<std::uint16_t> counter1;
  std::vector<std::uint16_t> counter2;  // HELLAS: the timeout (the format has no second count)

  [[nodiscard]] std::size_t size() const { return pulses.size(); }
};

class RecordingDecoder {
 public:
  // Reads the recording's structure and fits its clock (two streaming passes), then opens it for
  // decoding. `scan` is the scenario's sensor (scan.model must be the recording's format). Throws
  // owsim::Error naming the file for a recording that cannot be read, is empty or unsound.
  RecordingDecoder(std::filesystem::path path, const ScanParams& scan,
                   const RecordingDecoderOptions& options = {});
  ~RecordingDecoder();
  RecordingDecoder(const RecordingDecoder&) = delete;
  RecordingDecoder& operator=(const RecordingDecoder&) = delete;

  [[nodiscard]] const RecordingLayout& layout() const { return layout_; }
  [[nodiscard]] const ScanParams& scan() const { return scan_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  // The next frame, in file order; false once every pulse has been decoded. Reuses `frame`'s
  // buffers.
  bool next(DecodedFrame& frame);

  // Pulses (so far) whose time tag differs from the one their rebuilt time gives: 0 for an owsim
  // recording on the grid.
  [[nodiscard]] std::uint64_t time_tag_mismatches() const { return tag_mismatches_; }

 private:
  class WordSource;

  void decode_words(DecodedFrame& frame);

  std::filesystem::path path_;
  ScanParams scan_;
  RecordingLayout layout_;
  std::unique_ptr<WordSource> source_;
  std::uint64_t pulses_decoded_ = 0;
  std::uint64_t tag_mismatches_ = 0;
};

// The layout of a recording as `owsim run` writes it — whole frames from frame 0, on the scenario's
// pulse grid, a HELLAS file's header word first — which the decoder would find in such a file:
// for decoding frames held in memory (the run's own words) exactly as a file of them decodes.
[[nodiscard]] RecordingLayout grid_recording_layout(
    const ScanParams& scan, std::optional<std::uint32_t> hellas_header_word = std::nullopt);

// The decoder's step for one frame: `frame`'s frame, first_word and words set (the pulses from
// first_word on, as RecordingDecoder::next reads them), the rest filled from them — pulses, counters,
// sweep, β source. What RecordingDecoder::next does, for words read from anywhere. Thread-safe.
// Returns the pulses whose time tag disagrees with their rebuilt time.
std::uint64_t decode_frame_words(const ScanParams& scan, const RecordingLayout& layout,
                                 DecodedFrame& frame);

// "recording starts mid-frame …", "time on the scenario's pulse grid …": what the layout says, as
// lines for people (each ending in a newline).
[[nodiscard]] std::string describe(const RecordingLayout& layout, const ScanParams& scan);

}  // namespace owsim
