#include "io/recording/recording_check.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "io/recording/hellas_word.hpp"
#include "io/recording/milows_word.hpp"
#include "io/recording/word_file.hpp"
#include "sensor/hellas_scan.hpp"
#include "sensor/range_counter.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

// The time-tag clock of each format  (SENSOR-SPEC §8, pinned time tag)
struct TimeTagClock {
  double tick_s;
  std::uint32_t modulus;
};
constexpr TimeTagClock kMilowsClock{kMilowsTimeTagTickS, kMilowsTimeTagModulus};
constexpr TimeTagClock kHellasClock{kHellasTimeTagTickS, kHellasTimeTagModulus};

bool is_problem(RecordingIssueKind kind) { return kind < RecordingIssueKind::partial_frame; }

// Keeps the first `max_listed` problems and notes, counts all of them.
class IssueLog {
 public:
  explicit IssueLog(std::size_t max_listed) : max_listed_(max_listed) {}

  void add(std::uint64_t word, RecordingIssueKind kind, std::string description) {
    if (is_problem(kind)) {
      ++problem_count_;
      ++problem_counts_[std::string(to_string(kind))];
      if (problems_.size() < max_listed_) problems_.push_back({word, kind, std::move(description)});
    } else {
      ++note_count_;
      if (notes_.size() < max_listed_) notes_.push_back({word, kind, std::move(description)});
    }
  }

  void move_into(RecordingReport& report) {
    const auto by_word = [](const RecordingIssue& a, const RecordingIssue& b) {
      return a.word < b.word;
    };
    std::stable_sort(problems_.begin(), problems_.end(), by_word);
    std::stable_sort(notes_.begin(), notes_.end(), by_word);
    report.problems = std::move(problems_);
    report.notes = std::move(notes_);
    report.problem_count = problem_count_;
    report.note_count = note_count_;
    report.problem_counts = std::move(problem_counts_);
  }

 private:
  std::size_t max_listed_;
  std::vector<RecordingIssue> problems_, notes_;
  std::uint64_t problem_count_ = 0, note_count_ = 0;
  std::map<std::string, std::uint64_t> problem_counts_;
};

// Counts of every 12-bit counter value; summarised against the timeout.
class CounterHistogram {
 public:
  void add(std::uint16_t counter) { ++counts_[counter & kCounterMax]; }

  [[nodiscard]] CounterSummary summary(std::uint16_t timeout) const {
    CounterSummary s;
    for (std::size_t c = 0; c < counts_.size(); ++c) {
      if (c < timeout)
        s.valid += counts_[c];
      else if (c == timeout)
        s.timeouts += counts_[c];
      else
        s.beyond_timeout += counts_[c];
    }
    if (s.valid == 0) return s;
    const auto rank = [&](double p) {  // nearest rank: smallest c with cumulative ≥ ceil(p·n)
      const auto wanted = std::max<std::uint64_t>(
          1, static_cast<std::uint64_t>(std::ceil(p * static_cast<double>(s.valid))));
      std::uint64_t cumulative = 0;
      for (std::size_t c = 0; c < timeout; ++c) {
        cumulative += counts_[c];
        if (cumulative >= wanted) return static_cast<std::uint16_t>(c);
      }
      return static_cast<std::uint16_t>(timeout - 1);
    };
    s.min = rank(0.0);
    s.q1 = rank(0.25);
    s.median = rank(0.5);
    s.q3 = rank(0.75);
    s.max = rank(1.0);
    return s;
  }

 private:
  std::array<std::uint64_t, kCounterMax + 1> counts_{};
};

// One pulse as the structure check sees it, whatever the format (gates active-high here).
struct CheckedPulse {
  std::uint64_t word = 0;
  bool frame_gate = false;
  bool line_gate = false;
  std::uint16_t time_tag = 0;
  std::uint16_t counter1 = 0;
  std::uint16_t counter2 = 0;  // MilOWS only
};

struct PulseEvents {
  bool frame_start = false;     // first pulse after a frame gate (or of the file)
  bool line_start = false;      // first pulse after a line or frame gate (or of the file)
  bool frame_end = false;       // this pulse carries the frame gate
  bool complete_frame = false;  // ... and closes a frame of pulses_per_frame pulses
};

// Frame and line structure, time tags, counters and returns per fiber: what both formats share.
class StructureCheck {
 public:
  StructureCheck(const ScanParams& scan, TimeTagClock clock, bool second_counter, IssueLog& log)
      : fibers_per_line_(scan.fibers_per_line),
        pulses_per_frame_(scan.pulses_per_frame()),
        timeout_(scan.counter.timeout_counts),
        second_counter_(second_counter),
        clock_(clock),
        max_tag_step_(max_tag_step(scan.prf_hz, clock)),
        prf_hz_(scan.prf_hz),
        log_(log),
        returns_per_fiber_(static_cast<std::size_t>(std::max(0, scan.fibers_per_line))),
        second_returns_per_fiber_(second_counter ? returns_per_fiber_.size() : 0) {}

  PulseEvents add(const CheckedPulse& pulse) {
    PulseEvents events;
    events.frame_start = frame_pulses_ == 0;
    events.line_start = line_pulses_ == 0;
    if (pulses_ == 0) first_pulse_word_ = pulse.word;
    if (events.frame_start) frame_start_word_ = pulse.word;
    check_time_tag(pulse);
    check_counter(pulse.word, "counter 1", pulse.counter1);
    if (second_counter_) check_counter(pulse.word, "counter 2", pulse.counter2);

    ++pulses_;
    ++frame_pulses_;
    ++line_pulses_;
    if (line_start_known_) {
      account(line_pulses_ - 1, pulse.counter1, pulse.counter2);
    } else {
      first_line_.push_back({pulse.counter1, pulse.counter2});
    }

    if (pulse.line_gate || pulse.frame_gate) {
      end_line(pulse);
    } else if (line_pulses_ == fibers_per_line_) {
      if (!line_start_known_) resolve_first_line(0);  // no gate yet: assume a line start
      log_.add(pulse.word, RecordingIssueKind::line_length,
               "line reaches " + std::to_string(fibers_per_line_) + " pulses without a line gate");
      line_reported_ = true;
    }

    if (pulse.frame_gate) {
      events.frame_end = true;
      events.complete_frame = end_frame(pulse);
    } else if (frame_pulses_ == pulses_per_frame_) {
      log_.add(pulse.word, RecordingIssueKind::frame_length,
               "frame from word " + std::to_string(frame_start_word_) + " reaches " +
                   std::to_string(pulses_per_frame_) + " pulses without a frame gate");
      frame_reported_ = true;
    }
    return events;
  }

  [[nodiscard]] std::uint64_t frame_start_word() const { return frame_start_word_; }

  void finish(RecordingReport& report) {
    if (!line_start_known_) resolve_first_line(0);
    report.pulses = pulses_;
    report.complete_frames = complete_frames_;
    report.lines = lines_;
    report.leading_partial_pulses = leading_partial_pulses_;
    report.trailing_partial_pulses = static_cast<std::uint64_t>(frame_pulses_);
    if (leading_partial_pulses_ > 0) {
      log_.add(first_pulse_word_, RecordingIssueKind::partial_frame,
               "recording starts mid-frame: " + std::to_string(leading_partial_pulses_) +
                   " pulses before the first frame start");
    }
    if (frame_pulses_ > 0) {
      const std::string count = std::to_string(frame_pulses_);
      log_.add(frame_start_word_, RecordingIssueKind::partial_frame,
               seen_frame_gate_
                   ? "recording stops mid-frame: " + count + " pulses after the last frame gate"
                   : "no frame gate in the recording: " + count + " pulses of a partial frame");
    }
    report.returns_per_fiber = returns_per_fiber_;
    report.second_returns_per_fiber = second_returns_per_fiber_;
    report.returns = returns_;
    report.second_returns = second_returns_;
    report.counter1 = counter1_.summary(timeout_);
    if (second_counter_) report.counter2 = counter2_.summary(timeout_);
    report.reference_counter = reference_.summary(timeout_);

    TimeTagSummary& time = report.time;
    time.tick_s = clock_.tick_s;
    time.modulus = clock_.modulus;
    time.first_tag = first_tag_;
    time.last_tag = last_tag_;
    time.span_ticks = unwrapped_ticks_;
    time.span_s = static_cast<double>(unwrapped_ticks_) * clock_.tick_s;
    const std::int64_t end_ticks = first_tag_ + unwrapped_ticks_;
    time.wraps = end_ticks > 0 ? static_cast<std::uint64_t>(end_ticks / clock_.modulus) : 0;
    time.pulses_span_s =
        pulses_ > 1 && prf_hz_ > 0.0 ? static_cast<double>(pulses_ - 1) / prf_hz_ : 0.0;
  }

 private:
  struct PendingPulse {
    std::uint16_t counter1, counter2;
  };

  // floor(a + d) − floor(a) ≤ ceil(d) with d the pulse period in ticks.
  static std::uint32_t max_tag_step(double prf_hz, TimeTagClock clock) {
    if (!(prf_hz > 0.0)) return clock.modulus / 2;
    const double ticks_per_pulse = 1.0 / (prf_hz * clock.tick_s);
    return static_cast<std::uint32_t>(std::max(1.0, std::ceil(ticks_per_pulse - 1e-12)));
  }

  void check_time_tag(const CheckedPulse& pulse) {
    if (pulses_ == 0) {
      first_tag_ = last_tag_ = pulse.time_tag;
      return;
    }
    const std::uint32_t step = (pulse.time_tag + clock_.modulus - last_tag_) % clock_.modulus;
    std::int64_t signed_step = step;
    if (step > max_tag_step_) {
      if (step > clock_.modulus / 2) signed_step -= clock_.modulus;
      log_.add(pulse.word, RecordingIssueKind::time_tag_jump,
               "time tag jumps from " + std::to_string(last_tag_) + " to " +
                   std::to_string(pulse.time_tag) + " (" + (signed_step > 0 ? "+" : "") +
                   std::to_string(signed_step) + " ticks); consecutive pulses step 0.." +
                   std::to_string(max_tag_step_));
    }
    unwrapped_ticks_ += signed_step;
    last_tag_ = pulse.time_tag;
  }

  void check_counter(std::uint64_t word, const char* name, std::uint16_t counter) {
    if (counter <= timeout_) return;
    log_.add(word, RecordingIssueKind::counter_beyond_timeout,
             std::string(name) + " = " + std::to_string(counter) + " is beyond the timeout " +
                 std::to_string(timeout_));
  }

  // Statistics of one pulse at `slot` in its line (fiber = slot + 1; beyond the line: no fiber).
  void account(std::int64_t slot, std::uint16_t counter1, std::uint16_t counter2) {
    const bool has_fiber = slot >= 0 && slot < fibers_per_line_;
    const auto fiber = static_cast<std::size_t>(slot);
    const bool reference = slot == fibers_per_line_ - 1;
    (reference ? reference_ : counter1_).add(counter1);
    if (counter1 < timeout_) {
      ++returns_;
      if (has_fiber) ++returns_per_fiber_[fiber];
    }
    if (!second_counter_) return;
    if (!reference) counter2_.add(counter2);
    if (counter2 < timeout_) {
      ++second_returns_;
      if (has_fiber) ++second_returns_per_fiber_[fiber];
    }
  }

  // The first line's pulses wait until its end tells which slots they had.
  void resolve_first_line(std::int64_t first_slot) {
    for (std::size_t i = 0; i < first_line_.size(); ++i) {
      account(first_slot + static_cast<std::int64_t>(i), first_line_[i].counter1,
              first_line_[i].counter2);
    }
    first_line_.clear();
    first_line_.shrink_to_fit();
    line_start_known_ = true;
  }

  void end_line(const CheckedPulse& pulse) {
    const bool partial_first_line = !line_start_known_ && line_pulses_ < fibers_per_line_;
    if (pulse.frame_gate && !pulse.line_gate) {
      log_.add(pulse.word, RecordingIssueKind::frame_gate_without_line_gate,
               "frame gate without a line gate");
    } else if (line_pulses_ != fibers_per_line_ && !line_reported_ && !partial_first_line) {
      log_.add(pulse.word, RecordingIssueKind::line_length,
               "line of " + std::to_string(line_pulses_) + " pulses ends here, expected " +
                   std::to_string(fibers_per_line_));
    }
    if (!line_start_known_)
      resolve_first_line(std::max<std::int64_t>(0, fibers_per_line_ - line_pulses_));
    if (!partial_first_line) ++lines_;
    line_pulses_ = 0;
    line_reported_ = false;
  }

  // Returns whether the frame just closed is complete.
  bool end_frame(const CheckedPulse& pulse) {
    const bool complete = frame_pulses_ == pulses_per_frame_;
    if (complete) {
      ++complete_frames_;
    } else if (!seen_frame_gate_ && frame_pulses_ < pulses_per_frame_) {
      leading_partial_pulses_ = static_cast<std::uint64_t>(frame_pulses_);
    } else if (!frame_reported_) {
      log_.add(pulse.word, RecordingIssueKind::frame_length,
               "frame of " + std::to_string(frame_pulses_) + " pulses from word " +
                   std::to_string(frame_start_word_) + " ends here, expected " +
                   std::to_string(pulses_per_frame_));
    }
    seen_frame_gate_ = true;
    frame_pulses_ = 0;
    frame_reported_ = false;
    return complete;
  }

  std::int64_t fibers_per_line_;
  std::int64_t pulses_per_frame_;
  std::uint16_t timeout_;
  bool second_counter_;
  TimeTagClock clock_;
  std::uint32_t max_tag_step_;
  double prf_hz_;
  IssueLog& log_;

  std::uint64_t pulses_ = 0;
  std::uint64_t first_pulse_word_ = 0;
  // frames
  bool seen_frame_gate_ = false;
  std::int64_t frame_pulses_ = 0;
  std::uint64_t frame_start_word_ = 0;
  bool frame_reported_ = false;
  std::uint64_t complete_frames_ = 0;
  std::uint64_t leading_partial_pulses_ = 0;
  // lines
  std::int64_t line_pulses_ = 0;
  bool line_start_known_ = false;
  bool line_reported_ = false;
  std::uint64_t lines_ = 0;
  std::vector<PendingPulse> first_line_;
  // time tags
  std::uint16_t first_tag_ = 0, last_tag_ = 0;
  std::int64_t unwrapped_ticks_ = 0;
  // counters
  std::vector<std::uint64_t> returns_per_fiber_, second_returns_per_fiber_;
  std::uint64_t returns_ = 0, second_returns_ = 0;
  CounterHistogram counter1_, counter2_, reference_;
};

// A flag or field that real recordings may set; reported once, with its count.
struct FlagTally {
  std::uint64_t count = 0;
  std::uint64_t first_word = 0;
  void add(bool set, std::uint64_t word) {
    if (!set) return;
    if (count++ == 0) first_word = word;
  }
  void note(IssueLog& log, RecordingIssueKind kind, const std::string& what) const {
    if (count == 0) return;
    log.add(first_word, kind, what + " on " + std::to_string(count) + " words (the first here)");
  }
};

// MilOWS only: encoder range and direction within a frame, flag bits.
class MilowsCheck {
 public:
  explicit MilowsCheck(IssueLog& log) : log_(log) {}

  void add(const MilowsWord& word, std::uint64_t index, const PulseEvents& events) {
    crosstalk_.add(word.crosstalk, index);
    reserved_.add(word.reserved28, index);
    lut_.add(word.lut != 0, index);
    trigger_.add(word.trigger != 0, index);

    if (!seen_) min_ = max_ = word.encoder;
    seen_ = true;
    min_ = std::min(min_, word.encoder);
    max_ = std::max(max_, word.encoder);

    if (events.frame_start) {
      direction_ = 0;
      reversal_reported_ = false;
    } else if (word.encoder != previous_) {
      const int step = word.encoder > previous_ ? 1 : -1;
      if (direction_ == 0) {
        direction_ = step;
      } else if (step != direction_ && !reversal_reported_) {
        log_.add(index, RecordingIssueKind::encoder_reversal,
                 std::string("encoder reverses within the frame: counts were ") +
                     (direction_ > 0 ? "increasing" : "decreasing") + ", now " +
                     std::to_string(previous_) + " → " + std::to_string(word.encoder));
        reversal_reported_ = true;
      }
    }
    previous_ = word.encoder;
  }

  void finish(RecordingReport& report) const {
    crosstalk_.note(log_, RecordingIssueKind::crosstalk_flag, "crosstalk flag set");
    reserved_.note(log_, RecordingIssueKind::reserved_bit, "reserved bit 28 set");
    lut_.note(log_, RecordingIssueKind::lut_bits, "LUT bits non-zero");
    trigger_.note(log_, RecordingIssueKind::trigger_bits, "trigger bits non-zero");
    if (!seen_) return;
    EncoderSummary encoder;
    encoder.min_counts = min_;
    encoder.max_counts = max_;
    const double beta_a = mirror_beta_deg_from_encoder(min_);
    const double beta_b = mirror_beta_deg_from_encoder(max_);
    encoder.mirror_beta_min_deg = std::min(beta_a, beta_b);
    encoder.mirror_beta_max_deg = std::max(beta_a, beta_b);
    report.encoder = encoder;
  }

 private:
  IssueLog& log_;
  FlagTally crosstalk_, reserved_, lut_, trigger_;
  bool seen_ = false;
  EncoderCount min_ = 0, max_ = 0, previous_ = 0;
  int direction_ = 0;
  bool reversal_reported_ = false;
};

// HELLAS only: MovDir constant within a frame, one NI per complete frame, Ain square wave.
class HellasCheck {
 public:
  explicit HellasCheck(IssueLog& log) : log_(log) {}

  void add(const HellasWord& word, std::uint64_t index, const PulseEvents& events,
           std::uint64_t frame_start_word) {
    if (events.frame_start) {
      mov_dir_ = word.mov_dir;
      mov_dir_reported_ = false;
      ni_in_frame_ = 0;
    } else if (word.mov_dir != mov_dir_ && !mov_dir_reported_) {
      log_.add(index, RecordingIssueKind::mov_dir_change,
               std::string("MovDir changes within the frame from word ") +
                   std::to_string(frame_start_word) + " (" + (mov_dir_ ? "1" : "0") + " → " +
                   (word.mov_dir ? "1" : "0") + ")");
      mov_dir_reported_ = true;
    }
    if (word.ni) {
      ++ni_marks_;
      if (++ni_in_frame_ == 1) {
        first_ni_word_ = index;
      } else if (ni_in_frame_ == 2) {
        log_.add(index, RecordingIssueKind::ni_count,
                 "second NI mark in the frame (the first at word " +
                     std::to_string(first_ni_word_) + ")");
      }
    }
    if (events.complete_frame && ni_in_frame_ == 0) {
      log_.add(index, RecordingIssueKind::ni_count,
               "frame from word " + std::to_string(frame_start_word) + " has no NI mark");
    }
    if (has_previous_) {
      const bool expected = events.line_start ? !previous_ain_ : previous_ain_;
      ain_.add(word.ain != expected, index);
    }
    has_previous_ = true;
    previous_ain_ = word.ain;
  }

  void finish(RecordingReport& report) const {
    ain_.note(log_, RecordingIssueKind::ain_pattern,
              "Ain does not toggle at every line gate and only there (owsim's square wave)");
    report.ni_marks = ni_marks_;
  }

 private:
  IssueLog& log_;
  bool mov_dir_ = false;
  bool mov_dir_reported_ = false;
  int ni_in_frame_ = 0;
  std::uint64_t first_ni_word_ = 0;
  std::uint64_t ni_marks_ = 0;
  bool has_previous_ = false;
  bool previous_ain_ = false;
  FlagTally ain_;
};

template <typename Word, typename OnWord>
void for_each_word(WordFileReader<Word>& reader, OnWord on_word) {
  std::vector<Word> chunk(kWordReadChunk);
  std::uint64_t index = 0;
  while (const std::size_t count = reader.read(chunk)) {
    for (std::size_t i = 0; i < count; ++i) on_word(chunk[i], index++);
  }
}

template <typename Word>
void fill_file_facts(RecordingReport& report, const WordFileReader<Word>& reader) {
  report.file_bytes = reader.file_bytes();
  report.word_bytes = sizeof(Word);
  report.words = reader.words_total();
  report.trailing_bytes = reader.trailing_bytes();
}

void check_milows(const std::filesystem::path& path, const ScanParams& scan, IssueLog& log,
                  RecordingReport& report) {
  MilowsWordReader reader(path);
  fill_file_facts(report, reader);
  StructureCheck structure(scan, kMilowsClock, true, log);
  MilowsCheck milows(log);
  for_each_word(reader, [&](std::uint64_t bits, std::uint64_t index) {
    const MilowsWord word = unpack_milows(bits);
    const PulseEvents events = structure.add(
        {index, word.frame_gate, word.line_gate, word.time_tag, word.counter1, word.counter2});
    milows.add(word, index, events);
  });
  structure.finish(report);
  milows.finish(report);
}

void check_hellas(const std::filesystem::path& path, const ScanParams& scan, IssueLog& log,
                  RecordingReport& report) {
  HellasWordReader reader(path);
  fill_file_facts(report, reader);
  StructureCheck structure(scan, kHellasClock, false, log);
  HellasCheck hellas(log);
  for_each_word(reader, [&](std::uint32_t bits, std::uint64_t index) {
    const HellasWord word = unpack_hellas(bits);
    if (word.select) {
      ++report.header_words;
      if (index == 0) {
        report.header =
            HellasHeaderSummary{word.counter, hellas_beta_from_header_code(word.counter)};
      } else {
        log.add(index, RecordingIssueKind::extra_header,
                "header word (Select = 1) after word 0; not counted as a pulse");
      }
      return;
    }
    if (index == 0) {
      log.add(index, RecordingIssueKind::missing_header,
              "first word is not a header word (Select = 0); read as a pulse");
    }
    // BT and ZT are active low: 0 marks the last pulse of a frame / line.
    const PulseEvents events =
        structure.add({index, !word.bt, !word.zt, word.time_tag, word.counter, 0});
    hellas.add(word, index, events, structure.frame_start_word());
  });
  structure.finish(report);
  hellas.finish(report);
}

}  // namespace

std::string_view to_string(RecordingIssueKind kind) {
  switch (kind) {
    case RecordingIssueKind::trailing_bytes:
      return "trailing_bytes";
    case RecordingIssueKind::empty_file:
      return "empty_file";
    case RecordingIssueKind::frame_length:
      return "frame_length";
    case RecordingIssueKind::line_length:
      return "line_length";
    case RecordingIssueKind::frame_gate_without_line_gate:
      return "frame_gate_without_line_gate";
    case RecordingIssueKind::time_tag_jump:
      return "time_tag_jump";
    case RecordingIssueKind::counter_beyond_timeout:
      return "counter_beyond_timeout";
    case RecordingIssueKind::encoder_reversal:
      return "encoder_reversal";
    case RecordingIssueKind::missing_header:
      return "missing_header";
    case RecordingIssueKind::extra_header:
      return "extra_header";
    case RecordingIssueKind::mov_dir_change:
      return "mov_dir_change";
    case RecordingIssueKind::ni_count:
      return "ni_count";
    case RecordingIssueKind::partial_frame:
      return "partial_frame";
    case RecordingIssueKind::crosstalk_flag:
      return "crosstalk_flag";
    case RecordingIssueKind::reserved_bit:
      return "reserved_bit";
    case RecordingIssueKind::lut_bits:
      return "lut_bits";
    case RecordingIssueKind::trigger_bits:
      return "trigger_bits";
    case RecordingIssueKind::ain_pattern:
      return "ain_pattern";
  }
  return "unknown";
}

std::optional<SensorModel> recording_model_from_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".d64") return SensorModel::milows;
  if (extension == ".hellas") return SensorModel::hellas;
  return std::nullopt;
}

std::optional<SensorModel> parse_recording_format(std::string_view text) {
  if (text == "d64") return SensorModel::milows;
  if (text == "hellas") return SensorModel::hellas;
  return std::nullopt;
}

std::string_view recording_format_name(SensorModel model) {
  return model == SensorModel::milows ? "d64" : "hellas";
}

RecordingReport check_recording(const std::filesystem::path& path, const ScanParams& scan,
                                const RecordingCheckOptions& options) {
  RecordingReport report;
  report.path = path;
  report.model = scan.model;
  report.fibers_per_line = scan.fibers_per_line;
  report.pulses_per_frame = scan.pulses_per_frame();
  report.timeout_counts = scan.counter.timeout_counts;
  IssueLog log(options.max_listed);
  if (scan.model == SensorModel::milows) {
    check_milows(path, scan, log, report);
  } else {
    check_hellas(path, scan, log, report);
  }
  if (report.pulses == 0) log.add(0, RecordingIssueKind::empty_file, "the file holds no pulses");
  if (report.trailing_bytes > 0) {
    log.add(report.words, RecordingIssueKind::trailing_bytes,
            "file ends with " + std::to_string(report.trailing_bytes) + " bytes of an incomplete " +
                std::to_string(report.word_bytes) + "-byte word");
  }
  log.move_into(report);
  return report;
}

}  // namespace owsim
