#include "io/recording/recording_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>
#include <utility>

#include "geometry/error.hpp"
#include "io/recording/hellas_word.hpp"
#include "io/recording/milows_word.hpp"
#include "io/recording/word_file.hpp"
#include "sensor/fiber_layout.hpp"
#include "sensor/hellas_scan.hpp"
#include "sensor/motor_encoder.hpp"

namespace owsim {
namespace {

// How far the scenario's grid time may lie outside the window the tags leave and still count as
// on it: far below the pulse period (16 µs), far above double rounding.
constexpr double kGridToleranceS = 1e-6;
// Without a start hint, how long before the scenario's start_s a recording may begin.
constexpr double kStartSlackS = 1e-3;

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

// Problems after which the pulses cannot be numbered or their β rebuilt, or the file is not what
// the sensor wrote (a size that is not a whole number of words: cut, or not a word file).
// Counters beyond the timeout (read as no return), an encoder reversal (β is read per word) and a
// HELLAS file without header (read as pulses) are not.
bool blocks_decoding(RecordingIssueKind kind) {
  switch (kind) {
    case RecordingIssueKind::counter_beyond_timeout:
    case RecordingIssueKind::encoder_reversal:
    case RecordingIssueKind::missing_header:
      return false;
    case RecordingIssueKind::trailing_bytes:
    case RecordingIssueKind::empty_file:
    case RecordingIssueKind::frame_length:
    case RecordingIssueKind::line_length:
    case RecordingIssueKind::frame_gate_without_line_gate:
    case RecordingIssueKind::time_tag_jump:
    case RecordingIssueKind::extra_header:
    case RecordingIssueKind::mov_dir_change:
    case RecordingIssueKind::ni_count:
      return true;
    default:
      return false;  // notes
  }
}

void require_decodable(const std::filesystem::path& path, const RecordingReport& report) {
  if (report.trailing_bytes > 0) {
    throw input_error(path.string(), "cannot decode: " + std::to_string(report.file_bytes) +
                                         " bytes is not a whole number of " +
                                         std::to_string(report.word_bytes) + "-byte words (" +
                                         std::to_string(report.trailing_bytes) + " trailing byte" +
                                         (report.trailing_bytes == 1 ? "" : "s") + ")");
  }
  std::uint64_t blocking = 0;
  for (int k = 0; k <= static_cast<int>(RecordingIssueKind::ain_pattern); ++k) {
    const auto kind = static_cast<RecordingIssueKind>(k);
    const auto found = report.problem_counts.find(std::string(to_string(kind)));
    if (blocks_decoding(kind) && found != report.problem_counts.end()) blocking += found->second;
  }
  if (blocking == 0) return;
  std::string first = "its frame/line structure is unsound";
  for (const RecordingIssue& issue : report.problems) {
    if (blocks_decoding(issue.kind)) {
      first = "word " + std::to_string(issue.word) + ": " + issue.description;
      break;
    }
  }
  throw input_error(path.string(), "cannot decode: " + first + " (" + std::to_string(blocking) +
                                       " such problem" + (blocking == 1 ? "" : "s") +
                                       "; `owsim info` lists them)");
}

struct TagClock {
  double tick_s;
  std::uint32_t modulus;
};

TagClock tag_clock(SensorModel model) {
  return model == SensorModel::milows ? TagClock{kMilowsTimeTagTickS, kMilowsTimeTagModulus}
                                      : TagClock{kHellasTimeTagTickS, kHellasTimeTagModulus};
}

// One word as the decoder needs it, whatever the format (gates active-high). The two gates lie
// apart: side by side, GCC copied them into a Pulse as one half-word read back from their two
// byte stores, a store-forwarding stall that took half of decode_frame_words' time.
struct WordFields {
  bool header = false;  // HELLAS Select = 1
  bool frame_gate = false;
  std::uint16_t time_tag = 0;
  bool line_gate = false;
  std::uint16_t counter1 = 0;
  std::uint16_t counter2 = 0;
  EncoderCount encoder = 0;
  bool ni = false;
  bool mov_dir = false;
};

// Inlined into decode_frame_words' loop, which takes it for one model at a time.
[[gnu::always_inline]] inline WordFields fields_of(SensorModel model, std::uint64_t bits,
                                                   std::uint16_t timeout) {
  WordFields out;
  if (model == SensorModel::milows) {
    const MilowsWord word = unpack_milows(bits);
    out.frame_gate = word.frame_gate;
    out.line_gate = word.line_gate;
    out.time_tag = word.time_tag;
    out.counter1 = word.counter1;
    out.counter2 = word.counter2;
    out.encoder = word.encoder;
    return out;
  }
  const HellasWord word = unpack_hellas(static_cast<std::uint32_t>(bits));
  out.header = word.select;
  out.frame_gate = !word.bt;  // BT and ZT are active low
  out.line_gate = !word.zt;
  out.time_tag = word.time_tag;
  out.counter1 = word.counter;
  out.counter2 = timeout;
  out.ni = word.ni;
  out.mov_dir = word.mov_dir;
  return out;
}

// What one pass over the time tags and the first gates says.
struct TagPass {
  std::uint64_t pulses = 0;
  std::optional<std::uint64_t> first_frame_gate;  // pulse index (0-based, headers excluded)
  std::optional<std::uint64_t> first_line_gate;
  // The window for t0' (t0 modulo the tag wrap): u_i·tick − i/PRF ≤ t0' < (u_i + 1)·tick − i/PRF.
  double low_s = -std::numeric_limits<double>::infinity();
  double high_s = std::numeric_limits<double>::infinity();
};

}  // namespace

// Streams the words of a recording as 64-bit values (HELLAS words zero-extended).
class RecordingDecoder::WordSource {
 public:
  WordSource(const std::filesystem::path& path, SensorModel model) {
    if (model == SensorModel::milows) {
      milows_ = std::make_unique<MilowsWordReader>(path);
      milows_buffer_.resize(kWordReadChunk);
    } else {
      hellas_ = std::make_unique<HellasWordReader>(path);
      hellas_buffer_.resize(kWordReadChunk);
    }
  }

  bool next(std::uint64_t& word) {
    if (position_ == count_) {
      position_ = 0;
      count_ = milows_ ? milows_->read(milows_buffer_) : hellas_->read(hellas_buffer_);
      if (count_ == 0) return false;
    }
    word = milows_ ? milows_buffer_[position_] : hellas_buffer_[position_];
    ++position_;
    return true;
  }

 private:
  std::unique_ptr<MilowsWordReader> milows_;
  std::unique_ptr<HellasWordReader> hellas_;
  std::vector<std::uint64_t> milows_buffer_;
  std::vector<std::uint32_t> hellas_buffer_;
  std::size_t position_ = 0, count_ = 0;
};

std::string_view to_string(RecordingTiming timing) {
  return timing == RecordingTiming::scenario_grid ? "scenario_grid" : "fitted";
}

std::string_view to_string(MirrorBetaSource source) {
  switch (source) {
    case MirrorBetaSource::encoder:
      return "encoder";
    case MirrorBetaSource::ni_mark:
      return "ni_mark";
    case MirrorBetaSource::header:
      return "header";
    case MirrorBetaSource::nominal:
      return "nominal";
  }
  return "nominal";
}

double RecordingLayout::pulse_time_s(const ScanParams& scan, std::int64_t frame, int pulse) const {
  if (timing == RecordingTiming::scenario_grid) return owsim::pulse_time_s(scan, frame, pulse);
  const std::int64_t offset = frame * scan.pulses_per_frame() + pulse - first_global_pulse;
  return first_pulse_time_s + static_cast<double>(offset) / scan.prf_hz;
}

RecordingDecoder::RecordingDecoder(std::filesystem::path path, const ScanParams& scan,
                                   const RecordingDecoderOptions& options)
    : path_(std::move(path)), scan_(scan) {
  // Pass 1: the frame/line structure, as `owsim info` checks it.
  layout_.check = check_recording(path_, scan_);
  require_decodable(path_, layout_.check);
  const RecordingReport& check = layout_.check;
  if (check.pulses == 0) throw input_error(path_.string(), "cannot decode: no pulses");
  if (check.header) layout_.hellas_header_code = check.header->beta_code;
  layout_.first_pulse_word = check.header_words > 0 ? 1 : 0;
  layout_.pulses = check.pulses;
  layout_.time_tag_wraps = check.time.wraps;

  // Pass 2: the time tags and the first gates.
  const TagClock clock = tag_clock(scan_.model);
  TagPass tags;
  {
    WordSource source(path_, scan_.model);
    std::uint64_t bits = 0;
    std::uint64_t index = 0;
    std::int64_t unwrapped = 0;
    std::uint16_t last_tag = 0;
    while (source.next(bits)) {
      const std::uint64_t word_index = index++;
      if (word_index < layout_.first_pulse_word) {
        layout_.hellas_header_word = static_cast<std::uint32_t>(bits);
        continue;
      }
      const WordFields word = fields_of(scan_.model, bits, scan_.counter.timeout_counts);
      const std::uint64_t i = tags.pulses++;
      if (i == 0) {
        unwrapped = word.time_tag;
      } else {
        std::int64_t step = (word.time_tag + clock.modulus - last_tag) % clock.modulus;
        if (step > clock.modulus / 2) step -= clock.modulus;
        unwrapped += step;
      }
      last_tag = word.time_tag;
      if (word.frame_gate && !tags.first_frame_gate) tags.first_frame_gate = i;
      if (word.line_gate && !tags.first_line_gate) tags.first_line_gate = i;
      const double since_first_s = static_cast<double>(i) / scan_.prf_hz;
      const double tag_s = static_cast<double>(unwrapped) * clock.tick_s;
      tags.low_s = std::max(tags.low_s, tag_s - since_first_s);
      tags.high_s = std::min(tags.high_s, tag_s + clock.tick_s - since_first_s);
    }
  }
  if (tags.pulses != layout_.pulses) {
    throw input_error(path_.string(), "changed while being read (" +
                                          std::to_string(layout_.pulses) + " pulses, then " +
                                          std::to_string(tags.pulses) + ")");
  }

  // t0 modulo the wrap, then the wrap nearest the hint.
  const double wrap_s = clock.modulus * clock.tick_s;
  const double middle = 0.5 * (tags.low_s + tags.high_s);
  const bool consistent = tags.low_s <= tags.high_s;
  layout_.tag_window_s = consistent ? tags.high_s - tags.low_s : 0.0;
  layout_.tag_misfit_s = consistent ? 0.0 : tags.low_s - tags.high_s;
  // With a hint: the wrap nearest it. Without: the first time from start_s on (a little slack, so
  // a recording starting at start_s is not pushed a whole wrap later by rounding).
  const double anchor =
      options.start_hint_s ? *options.start_hint_s : scan_.start_s + 0.5 * wrap_s - kStartSlackS;
  if (!std::isfinite(anchor)) throw Error("decode: the start hint is not finite");
  const double t0 = middle + std::round((anchor - middle) / wrap_s) * wrap_s;

  // The scenario's pulse grid: start_s + n/PRF.
  const std::int64_t per_frame = scan_.pulses_per_frame();
  const double grid_position = (t0 - scan_.start_s) * scan_.prf_hz;
  const auto grid_pulse = static_cast<std::int64_t>(std::llround(grid_position));
  const double grid_time = scan_.start_s + static_cast<double>(grid_pulse) / scan_.prf_hz;
  const bool in_window = layout_.tag_misfit_s <= kGridToleranceS &&
                         std::abs(grid_time - t0) <= 0.5 * layout_.tag_window_s + kGridToleranceS;
  const std::int64_t grid_pulse_in_frame =
      grid_pulse - floor_div(grid_pulse, per_frame) * per_frame;

  std::int64_t first_in_frame = 0;
  bool on_grid = false;
  if (tags.first_frame_gate) {
    first_in_frame =
        (per_frame - 1 - static_cast<std::int64_t>(*tags.first_frame_gate)) % per_frame;
    if (first_in_frame < 0) first_in_frame += per_frame;
    on_grid = in_window && grid_pulse_in_frame == first_in_frame;
  } else {
    // No frame gate: only the grid can say which pulse of its frame each word is.
    const std::int64_t fibers = scan_.fibers_per_line;
    const bool slot_agrees =
        !tags.first_line_gate ||
        (grid_pulse_in_frame + static_cast<std::int64_t>(*tags.first_line_gate)) % fibers ==
            fibers - 1;
    if (!in_window || !slot_agrees) {
      throw input_error(path_.string(),
                        "cannot decode: no frame gate in the recording, and its time tags do not "
                        "fall on the scenario's pulse grid, so its pulses cannot be numbered");
    }
    first_in_frame = grid_pulse_in_frame;
    on_grid = true;
  }
  if (on_grid) {
    layout_.timing = RecordingTiming::scenario_grid;
    layout_.first_global_pulse = grid_pulse;
  } else {
    layout_.timing = RecordingTiming::fitted;
    layout_.first_global_pulse =
        first_in_frame + per_frame * static_cast<std::int64_t>(std::llround(
                                         (grid_position - static_cast<double>(first_in_frame)) /
                                         static_cast<double>(per_frame)));
  }
  layout_.first_frame = floor_div(layout_.first_global_pulse, per_frame);
  layout_.first_pulse_in_frame = static_cast<int>(first_in_frame);
  const std::int64_t last_pulse =
      layout_.first_global_pulse + static_cast<std::int64_t>(layout_.pulses) - 1;
  layout_.last_frame = floor_div(last_pulse, per_frame);
  layout_.last_pulse_in_frame = static_cast<int>(last_pulse - layout_.last_frame * per_frame);
  layout_.frames = static_cast<std::uint64_t>(layout_.last_frame - layout_.first_frame + 1);
  layout_.first_pulse_time_s = on_grid ? grid_time : t0;
  layout_.last_pulse_time_s =
      layout_.pulse_time_s(scan_, layout_.last_frame, layout_.last_pulse_in_frame);

  // Pass 3 (next()): the words, frame by frame.
  source_ = std::make_unique<WordSource>(path_, scan_.model);
  std::uint64_t skipped = 0;
  for (std::uint64_t i = 0; i < layout_.first_pulse_word; ++i) source_->next(skipped);
}

RecordingDecoder::~RecordingDecoder() = default;

bool RecordingDecoder::next(DecodedFrame& frame) {
  if (pulses_decoded_ >= layout_.pulses) return false;
  const std::int64_t per_frame = scan_.pulses_per_frame();
  const std::int64_t n = layout_.first_global_pulse + static_cast<std::int64_t>(pulses_decoded_);
  frame.frame = floor_div(n, per_frame);
  frame.first_word = layout_.first_pulse_word + pulses_decoded_;
  frame.pulses.clear();
  frame.words.clear();
  frame.counter1.clear();
  frame.counter2.clear();
  for (auto k = static_cast<int>(n - frame.frame * per_frame);
       k < per_frame && pulses_decoded_ < layout_.pulses; ++k) {
    std::uint64_t bits = 0;
    if (!source_->next(bits)) {
      throw input_error(path_.string(), "ends early, after " + std::to_string(pulses_decoded_) +
                                            " of " + std::to_string(layout_.pulses) + " pulses");
    }
    ++pulses_decoded_;
    frame.words.push_back(bits);
  }
  decode_words(frame);
  return true;
}

void RecordingDecoder::decode_words(DecodedFrame& frame) {
  tag_mismatches_ += decode_frame_words(scan_, layout_, frame);
}

namespace {

// Mirror β by encoder count (index count + 32768): the inverse §3 polynomial solved once per count
// for the whole process (65,536 Newton solves, a few milliseconds), not once per pulse.
const std::vector<double>& mirror_beta_by_encoder() {
  static const std::vector<double> table = [] {
    std::vector<double> out(std::size_t{1} << 16);
    for (std::size_t k = 0; k < out.size(); ++k) {
      out[k] = mirror_beta_deg_from_encoder(static_cast<EncoderCount>(static_cast<int>(k) - 32768));
    }
    return out;
  }();
  return table;
}

// HELLAS: the frame's mirror β from its NI mark, the file's header word or the nominal start.
void decode_hellas_beta(const ScanParams& scan, const RecordingLayout& layout,
                        DecodedFrame& frame) {
  const double maf = hellas_mirror_angle_factor_deg(scan);
  const int direction = frame.pulses.front().mov_dir != 0 ? -1 : 1;
  const int first_pulse = frame.pulses.front().index;
  int ni_pulse = -1;
  for (std::size_t j = 0; j < frame.words.size(); ++j) {
    if (unpack_hellas(static_cast<std::uint32_t>(frame.words[j])).ni) {
      ni_pulse = frame.pulses[j].index;
      break;
    }
  }
  frame.ni_pulse = ni_pulse;
  // Mirror β of pulse 0 of the frame, from whichever reference the frame has.
  double beta_zero = 0.0;
  if (ni_pulse >= 0) {
    frame.beta_source = MirrorBetaSource::ni_mark;
    beta_zero = hellas_mirror_beta_deg(scan, 0, ni_pulse, direction);
  } else if (frame.first_word == layout.first_pulse_word && layout.hellas_header_code) {
    // The header holds the mirror angle before the file's first pulse: β of that pulse.
    frame.beta_source = MirrorBetaSource::header;
    beta_zero =
        hellas_beta_from_header_code(*layout.hellas_header_code) - direction * first_pulse * maf;
  } else {
    frame.beta_source = MirrorBetaSource::nominal;
    beta_zero = -0.5 * scan.sweep_deg * direction;
  }
  frame.sweep.direction = direction;
  frame.sweep.mirror_beta_start_deg = beta_zero;
  for (Pulse& pulse : frame.pulses) {
    pulse.mirror_beta_deg = beta_zero + direction * pulse.index * maf;
    pulse.beta_deg = pulse.mirror_beta_deg + sawtooth_deg(scan, pulse.fiber);
  }
}

}  // namespace

RecordingLayout grid_recording_layout(const ScanParams& scan,
                                      std::optional<std::uint32_t> hellas_header_word) {
  RecordingLayout layout;
  layout.timing = RecordingTiming::scenario_grid;
  if (scan.model == SensorModel::hellas && hellas_header_word) {
    layout.hellas_header_word = *hellas_header_word;
    layout.hellas_header_code = unpack_hellas(*hellas_header_word).counter;
    layout.first_pulse_word = 1;
  }
  layout.first_pulse_time_s = owsim::pulse_time_s(scan, 0, 0);
  return layout;
}

std::uint64_t decode_frame_words(const ScanParams& scan, const RecordingLayout& layout,
                                 DecodedFrame& frame) {
  const std::int64_t per_frame = scan.pulses_per_frame();
  const auto first_pulse = static_cast<int>(
      layout.first_global_pulse + static_cast<std::int64_t>(frame.first_word) -
      static_cast<std::int64_t>(layout.first_pulse_word) - frame.frame * per_frame);
  // A frame as the pattern numbers it; the decoded fields replace the pattern's below.
  FrameSweep pattern;
  pattern.frame = frame.frame;
  pattern.direction = (frame.frame & 1) == 0 ? 1 : -1;
  const std::vector<double>& mirror_beta = mirror_beta_by_encoder();
  std::uint64_t mismatches = 0;
  frame.pulses.clear();
  frame.counter1.clear();
  frame.counter2.clear();
  // What pulse_of_frame gives that depends on the slot alone (fiber, reference fiber, α, β_FC),
  // once per slot: the pattern's β and encoder of each pulse would only be replaced (MilOWS), and
  // HELLAS's linear β is taken alone.
  const int per_line = scan.fibers_per_line;
  if (!frame.words.empty()) {  // pulse_of_frame's error for a pulse outside the frame
    (void)pulse_of_frame(scan, pattern, first_pulse);
    (void)pulse_of_frame(scan, pattern, first_pulse + static_cast<int>(frame.words.size()) - 1);
  }
  std::vector<Pulse> by_slot(static_cast<std::size_t>(per_line));
  std::vector<double> sawtooth(static_cast<std::size_t>(per_line));
  for (int s = 0; s < per_line && s < per_frame; ++s) {
    const Pulse& pulse = by_slot[static_cast<std::size_t>(s)] = pulse_of_frame(scan, pattern, s);
    sawtooth[static_cast<std::size_t>(s)] = sawtooth_deg(scan, pulse.fiber);
  }
  // The words' time tags and the pulses' times, checked after the loop (the MilOWS tags a batch at
  // a time).
  thread_local std::vector<double> times;
  thread_local std::vector<std::uint16_t> tags, expected;
  times.resize(frame.words.size());
  tags.resize(frame.words.size());
  expected.resize(frame.words.size());
  // The loop for one model at a time: with the model a constant, a word's fields stay in
  // registers (a loop over both kept them in memory, and the gates' byte stores read back as one
  // half-word stalled every pulse).
  const auto decode_words = [&](auto model) {
    for (std::size_t j = 0; j < frame.words.size(); ++j) {
      const int k = first_pulse + static_cast<int>(j);
      const WordFields word = fields_of(model(), frame.words[j], scan.counter.timeout_counts);
      const auto slot = static_cast<std::size_t>(k % per_line);
      Pulse pulse = by_slot[slot];
      pulse.index = k;
      pulse.line = k / per_line;
      pulse.time_s = layout.pulse_time_s(scan, frame.frame, k);
      pulse.frame_gate = word.frame_gate;
      pulse.line_gate = word.line_gate;
      pulse.mov_dir = word.mov_dir ? 1 : 0;
      if constexpr (model() == SensorModel::milows) {
        pulse.encoder = word.encoder;
        pulse.mirror_beta_deg = mirror_beta[static_cast<std::size_t>(word.encoder + 32768)];
      } else {
        pulse.mirror_beta_deg = mirror_beta_deg(scan, pattern, k);
        pulse.encoder = 0;
      }
      pulse.beta_deg = pulse.mirror_beta_deg + sawtooth[slot];
      times[j] = pulse.time_s;
      tags[j] = word.time_tag;
      frame.pulses.push_back(pulse);
      frame.counter1.push_back(word.counter1);
      frame.counter2.push_back(word.counter2);
    }
  };
  if (scan.model == SensorModel::milows) {
    decode_words(std::integral_constant<SensorModel, SensorModel::milows>{});
    milows_time_tags(times, expected);
  } else {
    decode_words(std::integral_constant<SensorModel, SensorModel::hellas>{});
    for (std::size_t j = 0; j < times.size(); ++j) expected[j] = hellas_time_tag(times[j]);
  }
  for (std::size_t j = 0; j < tags.size(); ++j) mismatches += expected[j] != tags[j] ? 1 : 0;

  frame.ni_pulse = -1;
  frame.sweep = pattern;
  frame.sweep.start_s = layout.pulse_time_s(scan, frame.frame, 0);
  if (scan.model == SensorModel::hellas) {
    decode_hellas_beta(scan, layout, frame);
    return mismatches;
  }
  // MilOWS: β rises while the motor angle (and its encoder count) falls (§3: dφ/dβ < 0).
  frame.beta_source = MirrorBetaSource::encoder;
  const Pulse& first = frame.pulses.front();
  const Pulse& last = frame.pulses.back();
  if (last.encoder != first.encoder) frame.sweep.direction = last.encoder < first.encoder ? 1 : -1;
  for (Pulse& pulse : frame.pulses) pulse.mov_dir = frame.sweep.direction > 0 ? 0 : 1;
  frame.sweep.mirror_beta_start_deg = first.mirror_beta_deg - frame.sweep.direction *
                                                                  scan.sweep_deg * first.index /
                                                                  static_cast<double>(per_frame);
  return mismatches;
}

std::string describe(const RecordingLayout& layout, const ScanParams& scan) {
  const RecordingReport& check = layout.check;
  std::ostringstream out;
  out.precision(9);
  out << check.path.string() << ": " << (scan.model == SensorModel::milows ? "MilOWS" : "HELLAS")
      << " recording, " << layout.pulses << " pulses in " << layout.frames << " frame"
      << (layout.frames == 1 ? "" : "s") << " (" << layout.first_frame << ".." << layout.last_frame
      << " on the scenario's grid), " << check.complete_frames << " complete\n";
  if (layout.first_pulse_in_frame != 0) {
    out << "  starts mid-frame: the first word is pulse " << layout.first_pulse_in_frame
        << " of frame " << layout.first_frame << "\n";
  }
  if (layout.last_pulse_in_frame != scan.pulses_per_frame() - 1) {
    out << "  stops mid-frame: the last word is pulse " << layout.last_pulse_in_frame
        << " of frame " << layout.last_frame << "\n";
  }
  if (layout.timing == RecordingTiming::scenario_grid) {
    out << "  time: on the scenario's pulse grid, start_s + n/PRF, first pulse n = "
        << layout.first_global_pulse << " at " << layout.first_pulse_time_s << " s\n";
  } else {
    out << "  time: fitted to the time tags, first pulse at " << layout.first_pulse_time_s
        << " s (not on the scenario's pulse grid; tag window " << layout.tag_window_s * 1e6
        << " µs, misfit " << layout.tag_misfit_s * 1e6 << " µs)\n";
  }
  out << "  time tags " << check.time.first_tag << " → " << check.time.last_tag << ", wrapped "
      << layout.time_tag_wraps << " time" << (layout.time_tag_wraps == 1 ? "" : "s") << "; pulses "
      << layout.first_pulse_time_s << " → " << layout.last_pulse_time_s << " s\n";
  for (const RecordingIssue& note : check.notes) {
    out << "  note, word " << note.word << ": " << note.description << "\n";
  }
  for (const RecordingIssue& problem : check.problems) {
    out << "  problem (not blocking), word " << problem.word << ": " << problem.description << "\n";
  }
  return out.str();
}

}  // namespace owsim
