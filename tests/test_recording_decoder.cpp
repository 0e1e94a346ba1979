// Protects the decoder's numbering, timing and angles: words written from the scan pattern
// (sensor/scan_pattern.hpp, io/recording/frame_words.hpp) read back to the pattern's frame, pulse,
// fiber, time and α exactly and β within the encoder's / NI mark's quantisation — whole recordings,
// cut ones (mid-frame, mid-line), ones whose time tags wrap, ones off the scenario's pulse grid —
// and unsound recordings are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/recording/frame_words.hpp"
#include "io/recording/hellas_word.hpp"
#include "io/recording/milows_word.hpp"
#include "io/recording/recording_decoder.hpp"
#include "io/recording/word_file.hpp"
#include "sensor/hellas_scan.hpp"
#include "sensor/motor_encoder.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {
namespace {

constexpr std::uint64_t kSeed = 3;

// Every pulse of frames [first, first + count) as the simulator numbers them, with made-up
// counters (a return on some pulses, a second return on fewer).
struct Simulated {
  ScanParams scan;
  std::vector<std::int64_t> frame;
  std::vector<Pulse> pulses;
  std::vector<PulseReturns> returns;
  std::vector<FrameSweep> sweeps;    // by frame − first
  std::vector<std::uint64_t> words;  // packed, one per pulse (HELLAS: 32-bit values)
};

PulseReturns made_up_returns(const ScanParams& scan, std::int64_t frame, const Pulse& pulse) {
  PulseReturns out;
  const std::uint16_t timeout = scan.counter.timeout_counts;
  out.counter1 = out.counter2 = timeout;
  if (pulse.reference) {
    out.counter1 = scan.reference_counts;
    return out;
  }
  const std::int64_t key = frame * 7919 + pulse.index * 31;
  if (key % 5 == 0) out.counter1 = static_cast<std::uint16_t>(100 + key % 1800);
  if (key % 35 == 0) out.counter2 = static_cast<std::uint16_t>(out.counter1 + 5);
  return out;
}

Simulated simulate(const ScanParams& scan, std::int64_t first, int count) {
  Simulated out;
  out.scan = scan;
  const auto per_frame = static_cast<std::size_t>(scan.pulses_per_frame());
  std::vector<Pulse> pulses(per_frame);
  std::vector<PulseReturns> returns(per_frame);
  std::vector<std::uint64_t> milows(per_frame);
  std::vector<std::uint32_t> hellas(per_frame);
  for (std::int64_t f = first; f < first + count; ++f) {
    const FrameSweep sweep = frame_sweep(scan, kSeed, f);
    out.sweeps.push_back(sweep);
    for (std::size_t k = 0; k < per_frame; ++k) {
      pulses[k] = pulse_of_frame(scan, sweep, static_cast<int>(k));
      returns[k] = made_up_returns(scan, f, pulses[k]);
    }
    if (scan.model == SensorModel::milows) {
      pack_milows_frame(pulses, returns, milows);
      out.words.insert(out.words.end(), milows.begin(), milows.end());
    } else {
      pack_hellas_frame(scan, sweep, pulses, returns, hellas);
      out.words.insert(out.words.end(), hellas.begin(), hellas.end());
    }
    out.pulses.insert(out.pulses.end(), pulses.begin(), pulses.end());
    out.returns.insert(out.returns.end(), returns.begin(), returns.end());
    out.frame.insert(out.frame.end(), per_frame, f);
  }
  return out;
}

ScanParams milows_scan(double start_s = 0.0) {
  ScanParams scan;
  scan.start_s = start_s;
  return scan;
}

ScanParams hellas_scan() {
  ScanParams scan;
  scan.model = SensorModel::hellas;
  return scan;
}

// The largest mirror-β error of a MilOWS encoder word: half a count over the smallest |dφ/dβ|
// on ±30° (SENSOR-SPEC §3).
double encoder_beta_error_deg() {
  double slope = std::numeric_limits<double>::infinity();
  for (double beta = -30.0; beta <= 30.0; beta += 0.01) {
    slope = std::min(slope, std::abs(motor_angle_slope(beta)));
  }
  return 0.5 * kEncoderDegPerCount / slope + 1e-9;
}

class RecordingDecoderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("owsim_recording_decoder_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Writes pulses [begin, end) of `sim` (HELLAS: after `header`, if given).
  std::filesystem::path write(const Simulated& sim, std::size_t begin, std::size_t end,
                              std::optional<std::uint32_t> header = std::nullopt) {
    if (sim.scan.model == SensorModel::milows) {
      const auto path = dir_ / "flight.d64";
      MilowsWordWriter writer(path, {false});
      writer.write(std::span<const std::uint64_t>(sim.words).subspan(begin, end - begin));
      writer.commit();
      return path;
    }
    const auto path = dir_ / "flight.hellas";
    HellasWordWriter writer(path, {false});
    if (header) writer.write(*header);
    for (std::size_t i = begin; i < end; ++i)
      writer.write(static_cast<std::uint32_t>(sim.words[i]));
    writer.commit();
    return path;
  }

  std::filesystem::path dir_;
};

// Decodes the whole file and checks every pulse against sim's pulses [begin, ...).
void expect_pulses_match(RecordingDecoder& decoder, const Simulated& sim, std::size_t begin,
                         double beta_tolerance_deg, bool exact_time) {
  DecodedFrame frame;
  std::size_t i = begin;
  std::uint64_t word = decoder.layout().first_pulse_word;
  while (decoder.next(frame)) {
    ASSERT_EQ(frame.first_word, word);
    ASSERT_EQ(frame.pulses.size(), frame.words.size());
    for (std::size_t j = 0; j < frame.size(); ++j, ++i) {
      const Pulse& got = frame.pulses[j];
      const Pulse& want = sim.pulses[i];
      ASSERT_EQ(frame.frame, sim.frame[i]) << "pulse " << i;
      ASSERT_EQ(got.index, want.index) << "pulse " << i;
      ASSERT_EQ(got.line, want.line);
      ASSERT_EQ(got.fiber, want.fiber);
      ASSERT_EQ(got.reference, want.reference);
      ASSERT_EQ(got.frame_gate, want.frame_gate);
      ASSERT_EQ(got.line_gate, want.line_gate);
      ASSERT_EQ(got.mov_dir, want.mov_dir) << "pulse " << i;
      if (exact_time) {
        ASSERT_EQ(got.time_s, want.time_s) << "pulse " << i;
      } else {
        ASSERT_NEAR(got.time_s, want.time_s, 1.0 / sim.scan.prf_hz) << "pulse " << i;
      }
      if (!want.reference) ASSERT_EQ(got.alpha_deg, want.alpha_deg);
      ASSERT_NEAR(got.mirror_beta_deg, want.mirror_beta_deg, beta_tolerance_deg) << "pulse " << i;
      ASSERT_NEAR(got.beta_deg - got.mirror_beta_deg, want.beta_deg - want.mirror_beta_deg, 1e-12);
      ASSERT_EQ(frame.counter1[j], sim.returns[i].counter1);
      if (sim.scan.model == SensorModel::milows) {
        ASSERT_EQ(frame.counter2[j], sim.returns[i].counter2);
        ASSERT_EQ(got.encoder, want.encoder);
      }
      ASSERT_EQ(frame.words[j], sim.words[i]);
    }
    word += frame.size();
  }
  EXPECT_EQ(i - begin, decoder.layout().pulses);
}

TEST_F(RecordingDecoderTest, WholeMilowsFramesDecodeToThePatternOnTheGrid) {
  const Simulated sim = simulate(milows_scan(), 0, 3);
  RecordingDecoder decoder(write(sim, 0, sim.pulses.size()), sim.scan);
  const RecordingLayout& layout = decoder.layout();
  EXPECT_EQ(layout.timing, RecordingTiming::scenario_grid);
  EXPECT_EQ(layout.first_global_pulse, 0);
  EXPECT_EQ(layout.first_frame, 0);
  EXPECT_EQ(layout.last_frame, 2);
  EXPECT_EQ(layout.frames, 3u);
  EXPECT_EQ(layout.first_pulse_in_frame, 0);
  EXPECT_EQ(layout.last_pulse_in_frame, sim.scan.pulses_per_frame() - 1);
  EXPECT_EQ(layout.first_pulse_time_s, 0.0);
  EXPECT_EQ(layout.last_pulse_time_s, sim.pulses.back().time_s);
  EXPECT_EQ(layout.tag_misfit_s, 0.0);
  // The tags pin t0 to well under a pulse period.
  EXPECT_LT(layout.tag_window_s, 0.5 / sim.scan.prf_hz);
  expect_pulses_match(decoder, sim, 0, encoder_beta_error_deg(), true);
  EXPECT_EQ(decoder.time_tag_mismatches(), 0u);
}

TEST_F(RecordingDecoderTest, EncoderQuantisationBoundsTheMirrorAngleError) {
  // The figure the round trip relies on: half an encoder count is at most 0.0018° of mirror β.
  EXPECT_LT(encoder_beta_error_deg(), 0.0018);
  EXPECT_GT(encoder_beta_error_deg(), 0.0015);
}

TEST_F(RecordingDecoderTest, RecordingCutMidFrameAndMidLineIsNumberedFromTheFirstFrameGate) {
  const Simulated sim = simulate(milows_scan(), 4, 3);
  const std::size_t begin = 5000 + 17;  // mid-line
  const std::size_t end = sim.pulses.size() - 3000 - 5;
  RecordingDecoder decoder(write(sim, begin, end), sim.scan);
  const RecordingLayout& layout = decoder.layout();
  EXPECT_EQ(layout.timing, RecordingTiming::scenario_grid);
  EXPECT_EQ(layout.first_frame, 4);
  EXPECT_EQ(layout.first_pulse_in_frame, 5017);
  EXPECT_EQ(layout.last_frame, 6);
  EXPECT_EQ(layout.last_pulse_in_frame, sim.scan.pulses_per_frame() - 3006);
  EXPECT_EQ(layout.first_global_pulse, 4 * sim.scan.pulses_per_frame() + 5017);
  EXPECT_EQ(layout.check.leading_partial_pulses, sim.scan.pulses_per_frame() - 5017u);
  EXPECT_EQ(layout.check.trailing_partial_pulses, sim.scan.pulses_per_frame() - 3005u);
  EXPECT_EQ(layout.first_pulse_time_s, sim.pulses[begin].time_s);
  expect_pulses_match(decoder, sim, begin, encoder_beta_error_deg(), true);
  EXPECT_EQ(decoder.time_tag_mismatches(), 0u);
}

TEST_F(RecordingDecoderTest, TimeTagsWrappingInsideTheRecordingAreUnwrapped) {
  // The 16-bit MilOWS tag wraps every 6.5536 s; this recording crosses it.
  const Simulated sim = simulate(milows_scan(6.4), 0, 2);
  RecordingDecoder decoder(write(sim, 0, sim.pulses.size()), sim.scan);
  const RecordingLayout& layout = decoder.layout();
  EXPECT_EQ(layout.time_tag_wraps, 1u);
  EXPECT_EQ(layout.timing, RecordingTiming::scenario_grid);
  EXPECT_EQ(layout.first_pulse_time_s, 6.4);
  expect_pulses_match(decoder, sim, 0, encoder_beta_error_deg(), true);
}

TEST_F(RecordingDecoderTest, TheStartHintPicksTheTagWrap) {
  // Frames 30..31 fire near 10 s: the tags alone say 10 s − k · 6.5536 s. Without a hint the
  // decoder takes the first of those from start_s = 0 on.
  const Simulated sim = simulate(milows_scan(), 30, 2);
  const auto path = write(sim, 0, sim.pulses.size());
  {
    RecordingDecoder nearest_zero(path, sim.scan);
    EXPECT_EQ(nearest_zero.layout().timing, RecordingTiming::fitted);
    EXPECT_NEAR(nearest_zero.layout().first_pulse_time_s, sim.pulses[0].time_s - 6.5536, 2e-5);
  }
  RecordingDecoder decoder(path, sim.scan, {10.5});
  EXPECT_EQ(decoder.layout().timing, RecordingTiming::scenario_grid);
  EXPECT_EQ(decoder.layout().first_frame, 30);
  expect_pulses_match(decoder, sim, 0, encoder_beta_error_deg(), true);
}

TEST_F(RecordingDecoderTest, RecordingOffTheScenarioGridGetsFittedTimes) {
  // Words timed from start_s = 7.3 µs, decoded against a scenario starting at 0: the tags still
  // give every pulse's time to within a pulse period, and frames are numbered from the nearest.
  const Simulated sim = simulate(milows_scan(7.3e-6), 0, 2);
  RecordingDecoder decoder(write(sim, 0, sim.pulses.size()), milows_scan(0.0));
  const RecordingLayout& layout = decoder.layout();
  EXPECT_EQ(layout.timing, RecordingTiming::fitted);
  EXPECT_EQ(layout.first_frame, 0);
  EXPECT_NEAR(layout.first_pulse_time_s, 7.3e-6, 0.25 / sim.scan.prf_hz);
  expect_pulses_match(decoder, sim, 0, encoder_beta_error_deg(), false);
}

TEST_F(RecordingDecoderTest, RecordingWithoutFrameGateIsPlacedOnTheGrid) {
  const Simulated sim = simulate(milows_scan(), 1, 1);
  RecordingDecoder decoder(write(sim, 3000 + 5, 4000), sim.scan);
  EXPECT_EQ(decoder.layout().timing, RecordingTiming::scenario_grid);
  EXPECT_EQ(decoder.layout().first_frame, 1);
  EXPECT_EQ(decoder.layout().first_pulse_in_frame, 3005);
  EXPECT_EQ(decoder.layout().frames, 1u);
  expect_pulses_match(decoder, sim, 3005, encoder_beta_error_deg(), true);
}

TEST_F(RecordingDecoderTest, RecordingWithoutFrameGateOffTheGridIsRefused) {
  const Simulated sim = simulate(milows_scan(7.3e-6), 1, 1);
  const auto path = write(sim, 3000, 4000);
  try {
    RecordingDecoder decoder(path, milows_scan(0.0));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no frame gate"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

TEST_F(RecordingDecoderTest, UnsoundRecordingIsRefusedWithTheWordAtFault) {
  Simulated sim = simulate(milows_scan(), 0, 2);
  MilowsWord damaged = unpack_milows(sim.words[127]);
  damaged.line_gate = false;  // the first line runs on into the second
  sim.words[127] = pack(damaged);
  const auto path = write(sim, 0, sim.pulses.size());
  try {
    RecordingDecoder decoder(path, sim.scan);
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("cannot decode"), std::string::npos) << message;
    EXPECT_NE(message.find("word 127"), std::string::npos) << message;
  }
}

TEST_F(RecordingDecoderTest, RecordingCutInsideAWordIsRefused) {
  // Whole frames, sound but for the bytes of a word cut short: the size alone condemns it.
  for (const ScanParams& scan : {milows_scan(), hellas_scan()}) {
    const Simulated sim = simulate(scan, 0, 1);
    const auto path = write(sim, 0, sim.pulses.size());
    const std::uint64_t whole = std::filesystem::file_size(path);
    { std::ofstream(path, std::ios::binary | std::ios::app) << std::string(3, '\0'); }
    const std::string word_bytes = scan.model == SensorModel::milows ? "8" : "4";
    try {
      RecordingDecoder decoder(path, scan);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& error) {
      EXPECT_EQ(std::string(error.what()), path.string() +
                                               ": cannot decode: " + std::to_string(whole + 3) +
                                               " bytes is not a whole number of " + word_bytes +
                                               "-byte words (3 trailing bytes)");
    }
  }
}

TEST_F(RecordingDecoderTest, WrongFormatAndEmptyFileAreRefused) {
  const Simulated sim = simulate(milows_scan(), 0, 1);
  const auto path = write(sim, 0, 0);
  EXPECT_THROW(RecordingDecoder(path, sim.scan), Error);
  EXPECT_THROW(RecordingDecoder(dir_ / "missing.d64", sim.scan), Error);
}

TEST_F(RecordingDecoderTest, HellasBetaComesFromTheNiMark) {
  const ScanParams scan = hellas_scan();
  const Simulated sim = simulate(scan, 0, 3);
  RecordingDecoder decoder(
      write(sim, 0, sim.pulses.size(), hellas_file_header_word(sim.sweeps[0], 0.0)), scan);
  EXPECT_EQ(decoder.layout().first_pulse_word, 1u);
  EXPECT_EQ(decoder.layout().timing, RecordingTiming::scenario_grid);
  ASSERT_TRUE(decoder.layout().hellas_header_code.has_value());
  // β[k] = (k − k_NI) · MAF is within MAF/2 of the mirror's β  (SENSOR-SPEC §8, eq 4.3)
  const double half_maf = 0.5 * hellas_mirror_angle_factor_deg(scan) + 1e-12;
  RecordingDecoder again(decoder.path(), scan);
  DecodedFrame frame;
  while (again.next(frame)) {
    EXPECT_EQ(frame.beta_source, MirrorBetaSource::ni_mark);
    EXPECT_EQ(frame.ni_pulse,
              hellas_ni_pulse(scan, sim.sweeps[static_cast<std::size_t>(frame.frame)]));
  }
  expect_pulses_match(decoder, sim, 0, half_maf, true);
}

TEST_F(RecordingDecoderTest, HellasFramesWithoutNiMarkUseTheHeaderOrTheNominalSweep) {
  const ScanParams scan = hellas_scan();
  const Simulated sim = simulate(scan, 0, 3);
  const int per_frame = scan.pulses_per_frame();
  // Cut after frame 0's NI mark, and before frame 2's.
  const auto begin = static_cast<std::size_t>(hellas_ni_pulse(scan, sim.sweeps[0]) + 300);
  const auto end =
      static_cast<std::size_t>(2 * per_frame + hellas_ni_pulse(scan, sim.sweeps[2]) - 300);
  FrameSweep at_first = sim.sweeps[0];
  at_first.mirror_beta_start_deg = sim.pulses[begin].mirror_beta_deg;  // the mirror before it
  RecordingDecoder decoder(write(sim, begin, end, hellas_file_header_word(at_first, 0.0)), scan);
  std::vector<MirrorBetaSource> sources;
  DecodedFrame frame;
  std::size_t i = begin;
  while (decoder.next(frame)) {
    sources.push_back(frame.beta_source);
    // header: 0.01° code steps; nominal: the jitter the frame start is drawn with
    const double tolerance = frame.beta_source == MirrorBetaSource::header ? 0.005 + 1e-9
                             : frame.beta_source == MirrorBetaSource::nominal
                                 ? scan.frame_jitter_deg + 1e-9
                                 : 0.5 * hellas_mirror_angle_factor_deg(scan) + 1e-12;
    for (const Pulse& pulse : frame.pulses) {
      ASSERT_NEAR(pulse.mirror_beta_deg, sim.pulses[i].mirror_beta_deg, tolerance) << "pulse " << i;
      ++i;
    }
  }
  EXPECT_EQ(sources,
            (std::vector<MirrorBetaSource>{MirrorBetaSource::header, MirrorBetaSource::ni_mark,
                                           MirrorBetaSource::nominal}));
}

TEST_F(RecordingDecoderTest, DescribeReportsPartialFramesWrapsAndTiming) {
  const Simulated sim = simulate(milows_scan(6.4), 0, 3);
  RecordingDecoder decoder(write(sim, 100, sim.pulses.size() - 100), sim.scan);
  const std::string text = describe(decoder.layout(), sim.scan);
  EXPECT_NE(text.find("starts mid-frame: the first word is pulse 100 of frame 0"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("stops mid-frame"), std::string::npos) << text;
  EXPECT_NE(text.find("wrapped 1 time"), std::string::npos) << text;
  EXPECT_NE(text.find("on the scenario's pulse grid"), std::string::npos) << text;
}

}  // namespace
}  // namespace owsim
