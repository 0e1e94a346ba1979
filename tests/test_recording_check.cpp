// Protects `owsim info`'s checker: a correct recording reports its frames, lines, pulses and
// returns with no problem, and each kind of damage is reported at the word where it happens.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/recording/recording_check.hpp"
#include "test_recording_check_fixture.hpp"

namespace owsim {
namespace {

using fixture::kFibers;
using fixture::kLines;
using fixture::kNiPulse;
using fixture::kPulsesPerFrame;

class RecordingCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fixture::fresh_directory(std::string("recording_check_") +
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  RecordingReport check_milows(const std::vector<std::uint64_t>& words,
                               const RecordingCheckOptions& options = {}) {
    const auto path = dir_ / "flight.d64";
    fixture::write_words<std::uint64_t>(path, words);
    return check_recording(path, ScanParams{}, options);
  }
  RecordingReport check_hellas(const std::vector<std::uint32_t>& words) {
    const auto path = dir_ / "flight.hellas";
    fixture::write_words<std::uint32_t>(path, words);
    ScanParams scan;
    scan.model = SensorModel::hellas;
    return check_recording(path, scan);
  }

  std::filesystem::path dir_;
};

// Returns per fiber over whole frames, counted from the fixture's own pattern.
std::vector<std::uint64_t> expected_returns(int frames, bool second) {
  std::vector<std::uint64_t> per_fiber(kFibers, 0);
  for (std::int64_t line = 0; line < std::int64_t{frames} * kLines; ++line) {
    for (int slot = 0; slot < kFibers; ++slot) {
      const auto counter = second ? fixture::counter2(line, slot) : fixture::counter1(line, slot);
      if (counter < fixture::kTimeout) ++per_fiber[static_cast<std::size_t>(slot)];
    }
  }
  return per_fiber;
}

std::string describe(const RecordingReport& report) { return render_text(report); }

TEST_F(RecordingCheck, ValidMilowsFileHasThreeFramesAndNoProblems) {
  const RecordingReport r = check_milows(fixture::milows_words(3));
  EXPECT_EQ(r.words, 61'056u);
  EXPECT_EQ(r.pulses, 61'056u);
  EXPECT_EQ(r.complete_frames, 3u);
  EXPECT_EQ(r.lines, 477u);
  EXPECT_EQ(r.leading_partial_pulses, 0u);
  EXPECT_EQ(r.trailing_partial_pulses, 0u);
  EXPECT_EQ(r.trailing_bytes, 0u);
  EXPECT_EQ(r.problem_count, 0u) << describe(r);
  EXPECT_EQ(r.note_count, 0u) << describe(r);
  EXPECT_TRUE(r.sound());
  EXPECT_EQ(r.returns_per_fiber, expected_returns(3, false));
  EXPECT_EQ(r.second_returns_per_fiber, expected_returns(3, true));
  EXPECT_EQ(r.returns_per_fiber.back(), 477u);  // the reference fiber always returns
  // Optical counters are 100 + 7·slot for slots 0..126; the reference is always 10.
  EXPECT_EQ(r.counter1.min, 100);
  EXPECT_EQ(r.counter1.max, 100 + 7 * 126);
  EXPECT_EQ(r.counter1.valid + r.counter1.timeouts, 61'056u - 477u);
  EXPECT_EQ(r.reference_counter.valid, 477u);
  EXPECT_EQ(r.reference_counter.min, 10);
  EXPECT_EQ(r.reference_counter.median, 10);
  EXPECT_EQ(r.reference_counter.max, 10);
  ASSERT_TRUE(r.counter2.has_value());
  EXPECT_EQ(r.counter2->min, 1000);
  // Encoder range: the sweep is −18°..+18° (the fixture's encoder is the §3 polynomial).
  ASSERT_TRUE(r.encoder.has_value());
  EXPECT_NEAR(r.encoder->mirror_beta_min_deg, -18.0, 0.01);
  EXPECT_NEAR(r.encoder->mirror_beta_max_deg, 18.0, 0.01);
  EXPECT_EQ(r.encoder->min_counts, encoder_from_mirror_beta(18.0));
  EXPECT_EQ(r.encoder->max_counts, encoder_from_mirror_beta(-18.0));
  // Time: 61,055 pulse periods, to within one tick.
  EXPECT_EQ(r.time.first_tag, 0);
  EXPECT_EQ(r.time.last_tag, 61'055 * 10'000 / 61'111);
  EXPECT_NEAR(r.time.span_s, 61'055 / 61'111.0, 1e-4);
  EXPECT_EQ(r.time.wraps, 0u);
}

TEST_F(RecordingCheck, ValidHellasFileHasThreeFramesAndNoProblems) {
  const RecordingReport r = check_hellas(fixture::hellas_words(3));
  EXPECT_EQ(r.words, 61'057u);
  EXPECT_EQ(r.header_words, 1u);
  EXPECT_EQ(r.pulses, 61'056u);
  EXPECT_EQ(r.complete_frames, 3u);
  EXPECT_EQ(r.lines, 477u);
  EXPECT_EQ(r.problem_count, 0u) << describe(r);
  EXPECT_EQ(r.note_count, 0u) << describe(r);
  EXPECT_EQ(r.returns_per_fiber, expected_returns(3, false));
  EXPECT_TRUE(r.second_returns_per_fiber.empty());
  EXPECT_FALSE(r.counter2.has_value());
  EXPECT_FALSE(r.encoder.has_value());
  EXPECT_EQ(r.ni_marks, 3u);
  ASSERT_TRUE(r.header.has_value());
  EXPECT_EQ(r.header->beta_code, 248);  // round((−18 + 20.48) / 0.01)
  EXPECT_NEAR(r.header->mirror_beta_deg, -18.0, 1e-9);
  EXPECT_EQ(r.time.last_tag, 61'055 * 2'000 / 61'111);
}

TEST_F(RecordingCheck, TimeTagsWrappingAcrossTheirModulusAreFine) {
  // Pulse 400,000 is tag 65,454: the MilOWS tag wraps 65535 → 0 inside the file.
  const RecordingReport milows = check_milows(fixture::milows_words(3, 400'000));
  EXPECT_EQ(milows.problem_count, 0u) << describe(milows);
  EXPECT_EQ(milows.time.first_tag, 65'454);
  EXPECT_EQ(milows.time.wraps, 1u);
  EXPECT_NEAR(milows.time.span_s, 61'055 / 61'111.0, 1e-4);
  // Pulse 500,000 is tag 16,363: the HELLAS tag wraps 16383 → 0.
  const RecordingReport hellas = check_hellas(fixture::hellas_words(3, 500'000));
  EXPECT_EQ(hellas.problem_count, 0u) << describe(hellas);
  EXPECT_EQ(hellas.time.first_tag, 16'363);
  EXPECT_EQ(hellas.time.wraps, 1u);
  EXPECT_NEAR(hellas.time.span_s, 61'055 / 61'111.0, 5e-4);
}

TEST_F(RecordingCheck, TruncatedMidWordReportsTrailingBytes) {
  const auto path = dir_ / "cut.d64";
  fixture::write_words<std::uint64_t>(path, fixture::milows_words(3));
  std::filesystem::resize_file(path, 61'056 * 8 - 3);
  const RecordingReport r = check_recording(path, ScanParams{});
  EXPECT_EQ(r.words, 61'055u);
  EXPECT_EQ(r.trailing_bytes, 5u);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::trailing_bytes);
  EXPECT_EQ(r.problems[0].word, 61'055u);
  EXPECT_EQ(r.trailing_partial_pulses, static_cast<std::uint64_t>(kPulsesPerFrame - 1));

  // Three bytes after the last whole word.
  fixture::write_words<std::uint64_t>(path, fixture::milows_words(1));
  { std::ofstream(path, std::ios::binary | std::ios::app) << "abc"; }
  const RecordingReport three = check_recording(path, ScanParams{});
  EXPECT_EQ(three.trailing_bytes, 3u);
  EXPECT_EQ(three.complete_frames, 1u);
  ASSERT_EQ(three.problem_count, 1u) << describe(three);
  EXPECT_EQ(three.problems[0].kind, RecordingIssueKind::trailing_bytes);
  EXPECT_EQ(three.problems[0].word, static_cast<std::uint64_t>(kPulsesPerFrame));
}

// A recording may stop at any pulse (the operator stops it): a partial last frame is a note.
TEST_F(RecordingCheck, TruncatedMidFrameIsANoteNotAProblem) {
  auto words = fixture::milows_words(3);
  words.resize(50'000);
  const RecordingReport r = check_milows(words);
  EXPECT_EQ(r.problem_count, 0u) << describe(r);
  EXPECT_EQ(r.complete_frames, 2u);
  EXPECT_EQ(r.trailing_partial_pulses, 50'000u - 2 * kPulsesPerFrame);
  ASSERT_EQ(r.note_count, 1u);
  EXPECT_EQ(r.notes[0].kind, RecordingIssueKind::partial_frame);
  EXPECT_EQ(r.notes[0].word, 2u * kPulsesPerFrame);
}

// A recording may start at any pulse too; the fibers of its first, partial line are counted
// backwards from the first line gate.
TEST_F(RecordingCheck, RecordingStartingMidLineAssignsFibersFromTheFirstLineGate) {
  const auto all = fixture::milows_words(3);
  const std::size_t skipped = 7 * kFibers + 104;  // mid-line of line 7
  const std::vector<std::uint64_t> words(all.begin() + static_cast<std::ptrdiff_t>(skipped),
                                         all.end());
  const RecordingReport r = check_milows(words);
  EXPECT_EQ(r.problem_count, 0u) << describe(r);
  EXPECT_EQ(r.leading_partial_pulses, kPulsesPerFrame - skipped);
  EXPECT_EQ(r.complete_frames, 2u);
  EXPECT_EQ(r.lines, 3u * kLines - 8);  // the partial first line is not a line
  std::vector<std::uint64_t> expected(kFibers, 0);
  for (std::size_t n = skipped; n < all.size(); ++n) {
    const std::int64_t line = static_cast<std::int64_t>(n) / kFibers;
    const int slot = static_cast<int>(n % kFibers);
    if (fixture::counter1(line, slot) < fixture::kTimeout)
      ++expected[static_cast<std::size_t>(slot)];
  }
  EXPECT_EQ(r.returns_per_fiber, expected);
  ASSERT_EQ(r.note_count, 1u);
  EXPECT_EQ(r.notes[0].kind, RecordingIssueKind::partial_frame);
  EXPECT_EQ(r.notes[0].word, 0u);
}

constexpr std::uint64_t kFrameGate = std::uint64_t{1} << 31;
constexpr std::uint64_t kLineGate = std::uint64_t{1} << 30;

TEST_F(RecordingCheck, LineGateMovedOneWordLaterIsReportedWhereItIsMissing) {
  auto words = fixture::milows_words(3);
  const std::size_t w = kPulsesPerFrame + 5 * kFibers + 127;  // last pulse of line 5 of frame 1
  words[w] &= ~kLineGate;
  words[w + 1] |= kLineGate;
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 2u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::line_length);
  EXPECT_EQ(r.problems[0].word, w);  // 128 pulses and no line gate
  EXPECT_EQ(r.problems[1].kind, RecordingIssueKind::line_length);
  EXPECT_EQ(r.problems[1].word, w + 128);  // the next line is one pulse short
  EXPECT_EQ(r.complete_frames, 3u);
}

TEST_F(RecordingCheck, LineGateMovedOneWordEarlierIsReportedWhereTheLineEndsShort) {
  auto words = fixture::milows_words(3);
  const std::size_t w = 2 * kFibers + 127;
  words[w] &= ~kLineGate;
  words[w - 1] |= kLineGate;
  const RecordingReport r = check_milows(words);
  ASSERT_GE(r.problem_count, 1u);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::line_length);
  EXPECT_EQ(r.problems[0].word, w - 1);
  EXPECT_NE(r.problems[0].description.find("127 pulses"), std::string::npos)
      << r.problems[0].description;
}

TEST_F(RecordingCheck, RemovedFrameGateIsReportedAtTheWordThatShouldCarryIt) {
  auto words = fixture::milows_words(3);
  words[kPulsesPerFrame - 1] &= ~kFrameGate;
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 2u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::frame_length);
  EXPECT_EQ(r.problems[0].word, static_cast<std::uint64_t>(kPulsesPerFrame - 1));
  // The merged frame then sweeps back: its encoder reverses once frame 1 starts moving.
  EXPECT_EQ(r.problems[1].kind, RecordingIssueKind::encoder_reversal);
  EXPECT_GT(r.problems[1].word, static_cast<std::uint64_t>(kPulsesPerFrame - 1));
  EXPECT_EQ(r.complete_frames, 1u);
}

TEST_F(RecordingCheck, ExtraFrameGateMakesAShortFrame) {
  auto words = fixture::milows_words(3);
  const std::size_t w = kPulsesPerFrame + 10 * kFibers - 1;  // a line end inside frame 1
  words[w] |= kFrameGate;
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 2u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::frame_length);
  EXPECT_EQ(r.problems[0].word, w);
  EXPECT_EQ(r.problems[1].kind, RecordingIssueKind::frame_length);
  EXPECT_EQ(r.problems[1].word, 2u * kPulsesPerFrame - 1);
}

TEST_F(RecordingCheck, FrameGateWithoutLineGateIsAProblem) {
  auto words = fixture::milows_words(2);
  words[kPulsesPerFrame - 1] &= ~kLineGate;
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::frame_gate_without_line_gate);
  EXPECT_EQ(r.problems[0].word, static_cast<std::uint64_t>(kPulsesPerFrame - 1));
}

TEST_F(RecordingCheck, TimeTagJumpOfFiveTicksIsReportedOnce) {
  auto words = fixture::milows_words(2);
  std::size_t j = 12'345;  // a pulse whose tag equals its predecessor's, so the step becomes +5
  while ((words[j] >> 48) != (words[j - 1] >> 48)) ++j;
  for (std::size_t i = j; i < words.size(); ++i) {
    const std::uint64_t tag = (words[i] >> 48) + 5;
    words[i] = (words[i] & 0x0000'FFFF'FFFF'FFFFull) | (tag & 0xFFFF) << 48;
  }
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::time_tag_jump);
  EXPECT_EQ(r.problems[0].word, j);
  EXPECT_NE(r.problems[0].description.find("+5"), std::string::npos) << r.problems[0].description;
  EXPECT_NEAR(r.time.span_s, 2 * kPulsesPerFrame / 61'111.0 + 5e-4, 2e-4);
}

TEST_F(RecordingCheck, TimeTagGoingBackIsAJump) {
  auto words = fixture::milows_words(1);
  const std::size_t j = 777;
  const std::uint64_t tag = (words[j - 1] >> 48) - 1;
  words[j] = (words[j] & 0x0000'FFFF'FFFF'FFFFull) | (tag & 0xFFFF) << 48;
  const RecordingReport r = check_milows(words);
  ASSERT_GE(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::time_tag_jump);
  EXPECT_EQ(r.problems[0].word, j);
  EXPECT_NE(r.problems[0].description.find("-1 ticks"), std::string::npos)
      << r.problems[0].description;
}

TEST_F(RecordingCheck, CounterAboveTheTimeoutIsAProblem) {
  auto words = fixture::milows_words(1);
  words[5] = (words[5] & ~std::uint64_t{0xFFF}) | 3000;
  words[9] = (words[9] & ~(std::uint64_t{0xFFF} << 16)) | std::uint64_t{2067} << 16;
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 2u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::counter_beyond_timeout);
  EXPECT_EQ(r.problems[0].word, 5u);
  EXPECT_NE(r.problems[0].description.find("counter 1 = 3000"), std::string::npos);
  EXPECT_EQ(r.problems[1].word, 9u);
  EXPECT_NE(r.problems[1].description.find("counter 2 = 2067"), std::string::npos);
  EXPECT_EQ(r.counter1.beyond_timeout, 1u);
}

TEST_F(RecordingCheck, EncoderReversalWithinAFrameIsAProblem) {
  auto words = fixture::milows_words(2);
  // Frame 0 sweeps upward in β, so the encoder counts fall; make one step go back up.
  const std::size_t j = 5'000;
  const auto previous = static_cast<std::int16_t>(words[j - 1] >> 32);
  const auto back_up = static_cast<std::uint16_t>(previous + 3);
  words[j] = (words[j] & ~(std::uint64_t{0xFFFF} << 32)) | std::uint64_t{back_up} << 32;
  const RecordingReport r = check_milows(words);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::encoder_reversal);
  EXPECT_EQ(r.problems[0].word, j);
}

TEST_F(RecordingCheck, FlagBitsRealRecordingsMaySetAreNotes) {
  auto words = fixture::milows_words(1);
  words[10] |= std::uint64_t{1} << 29;  // crosstalk
  words[20] |= std::uint64_t{1} << 29;
  words[30] |= std::uint64_t{2} << 14;  // LUT
  words[40] |= std::uint64_t{1} << 12;  // trigger
  words[50] |= std::uint64_t{1} << 28;  // reserved
  const RecordingReport r = check_milows(words);
  EXPECT_EQ(r.problem_count, 0u) << describe(r);
  ASSERT_EQ(r.note_count, 4u) << describe(r);
  EXPECT_EQ(r.notes[0].kind, RecordingIssueKind::crosstalk_flag);
  EXPECT_EQ(r.notes[0].word, 10u);
  EXPECT_NE(r.notes[0].description.find("2 words"), std::string::npos);
  EXPECT_EQ(r.notes[1].kind, RecordingIssueKind::lut_bits);
  EXPECT_EQ(r.notes[2].kind, RecordingIssueKind::trigger_bits);
  EXPECT_EQ(r.notes[3].kind, RecordingIssueKind::reserved_bit);
  EXPECT_EQ(r.notes[3].word, 50u);
}

TEST_F(RecordingCheck, ListedProblemsAreCappedButAllCounted) {
  auto words = fixture::milows_words(1);
  for (std::size_t i = 0; i < 50; ++i)
    words[100 + i] = (words[100 + i] & ~std::uint64_t{0xFFF}) | 4000;
  RecordingCheckOptions options;
  options.max_listed = 20;
  const RecordingReport r = check_milows(words, options);
  EXPECT_EQ(r.problem_count, 50u);
  ASSERT_EQ(r.problems.size(), 20u);
  EXPECT_EQ(r.problems.front().word, 100u);
  EXPECT_EQ(r.problems.back().word, 119u);
  EXPECT_EQ(r.problem_counts.at("counter_beyond_timeout"), 50u);
  EXPECT_NE(render_text(r).find("and 30 more"), std::string::npos);
}

TEST_F(RecordingCheck, SecondHellasHeaderIsReportedAndNotCountedAsAPulse) {
  auto words = fixture::hellas_words(3);
  const std::size_t j = 30'000;
  words.insert(words.begin() + j, fixture::hellas_header(0.0, 0));
  const RecordingReport r = check_hellas(words);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::extra_header);
  EXPECT_EQ(r.problems[0].word, j);
  EXPECT_EQ(r.header_words, 2u);
  EXPECT_EQ(r.pulses, 61'056u);
  EXPECT_EQ(r.complete_frames, 3u);
}

TEST_F(RecordingCheck, HellasFileWithoutHeaderIsAProblem) {
  auto words = fixture::hellas_words(1);
  words.erase(words.begin());
  const RecordingReport r = check_hellas(words);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::missing_header);
  EXPECT_EQ(r.problems[0].word, 0u);
  EXPECT_EQ(r.complete_frames, 1u);
  EXPECT_FALSE(r.header.has_value());
}

constexpr std::uint32_t kZt = 1u << 30;
constexpr std::uint32_t kBt = 1u << 12;
constexpr std::uint32_t kNi = 1u << 14;
constexpr std::uint32_t kMovDir = 1u << 13;
constexpr std::uint32_t kAin = 1u << 15;

TEST_F(RecordingCheck, HellasGatesAreActiveLow) {
  auto words = fixture::hellas_words(2);
  const std::size_t w = 1 + 3 * kFibers + 127;  // a line end (word 0 is the header)
  ASSERT_EQ(words[w] & kZt, 0u);
  words[w] |= kZt;                // line gate cleared: the line runs on
  words[kPulsesPerFrame] |= kBt;  // the first frame's last pulse: frame gate cleared
  const RecordingReport r = check_hellas(words);
  ASSERT_EQ(r.problem_count, 4u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::line_length);
  EXPECT_EQ(r.problems[0].word, w);  // the merged line of 256 pulses is reported once
  EXPECT_EQ(r.problems[1].kind, RecordingIssueKind::frame_length);
  EXPECT_EQ(r.problems[1].word, static_cast<std::uint64_t>(kPulsesPerFrame));
  // The merged frame then holds frame 1's MovDir and NI too.
  EXPECT_EQ(r.problems[2].kind, RecordingIssueKind::mov_dir_change);
  EXPECT_EQ(r.problems[2].word, kPulsesPerFrame + 1u);
  EXPECT_EQ(r.problems[3].kind, RecordingIssueKind::ni_count);
  EXPECT_EQ(r.problems[3].word, 1u + kPulsesPerFrame + kNiPulse);
  EXPECT_EQ(r.complete_frames, 0u);
}

TEST_F(RecordingCheck, HellasMovDirMustStayConstantWithinAFrame) {
  auto words = fixture::hellas_words(2);
  const std::size_t j = 1 + 4'321;
  for (std::size_t i = j; i <= kPulsesPerFrame; ++i) words[i] |= kMovDir;
  const RecordingReport r = check_hellas(words);
  ASSERT_EQ(r.problem_count, 1u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::mov_dir_change);
  EXPECT_EQ(r.problems[0].word, j);
}

TEST_F(RecordingCheck, HellasNeedsExactlyOneNiPerCompleteFrame) {
  auto words = fixture::hellas_words(3);
  words[1 + kNiPulse] &= ~kNi;                             // frame 0: none
  const std::size_t extra = 1 + 2 * kPulsesPerFrame + 17;  // frame 2: two
  words[extra] |= kNi;
  const RecordingReport r = check_hellas(words);
  ASSERT_EQ(r.problem_count, 2u) << describe(r);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::ni_count);
  EXPECT_EQ(r.problems[0].word,
            static_cast<std::uint64_t>(kPulsesPerFrame));  // frame 0's last word
  EXPECT_EQ(r.problems[1].kind, RecordingIssueKind::ni_count);
  EXPECT_EQ(r.problems[1].word, 1u + 2 * kPulsesPerFrame + kNiPulse);  // the second mark
  EXPECT_EQ(r.ni_marks, 3u);
}

TEST_F(RecordingCheck, HellasAinOffOwsimsSquareWaveIsANote) {
  auto words = fixture::hellas_words(1);
  words[1 + 200] ^= kAin;
  const RecordingReport r = check_hellas(words);
  EXPECT_EQ(r.problem_count, 0u) << describe(r);
  ASSERT_EQ(r.note_count, 1u) << describe(r);
  EXPECT_EQ(r.notes[0].kind, RecordingIssueKind::ain_pattern);
  EXPECT_EQ(r.notes[0].word, 201u);
}

TEST_F(RecordingCheck, EmptyFileIsAProblemAndAMissingFileAnError) {
  const RecordingReport r = check_milows({});
  ASSERT_EQ(r.problem_count, 1u);
  EXPECT_EQ(r.problems[0].kind, RecordingIssueKind::empty_file);
  const auto missing = dir_ / "no_such.d64";
  try {
    (void)check_recording(missing, ScanParams{});
    FAIL() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

TEST_F(RecordingCheck, FormatFromExtensionAndOption) {
  EXPECT_EQ(recording_model_from_extension("a/flight.d64"), SensorModel::milows);
  EXPECT_EQ(recording_model_from_extension("FLIGHT.D64"), SensorModel::milows);
  EXPECT_EQ(recording_model_from_extension("x.hellas"), SensorModel::hellas);
  EXPECT_FALSE(recording_model_from_extension("x.bin").has_value());
  EXPECT_FALSE(recording_model_from_extension("d64").has_value());
  EXPECT_EQ(parse_recording_format("d64"), SensorModel::milows);
  EXPECT_EQ(parse_recording_format("hellas"), SensorModel::hellas);
  EXPECT_FALSE(parse_recording_format("milows").has_value());
}

TEST_F(RecordingCheck, TextAndJsonCarryTheCounts) {
  const RecordingReport r = check_milows(fixture::milows_words(3));
  const std::string text = render_text(r);
  EXPECT_NE(text.find("3 complete frames"), std::string::npos) << text;
  EXPECT_NE(text.find("477 lines"), std::string::npos) << text;
  EXPECT_NE(text.find("problems: none"), std::string::npos) << text;
  const nlohmann::json json = to_json(r);
  EXPECT_EQ(json.at("complete_frames"), 3);
  EXPECT_EQ(json.at("lines"), 477);
  EXPECT_EQ(json.at("pulses"), 61'056);
  EXPECT_EQ(json.at("format"), "d64");
  EXPECT_EQ(json.at("ok"), true);
  EXPECT_EQ(json.at("returns_per_fiber").size(), 128u);
  EXPECT_EQ(json.at("returns_per_fiber")[127], 477);
  EXPECT_TRUE(json.at("problems").empty());
  EXPECT_TRUE(json.at("header").is_null());
  EXPECT_EQ(json.at("encoder").at("max_counts"), encoder_from_mirror_beta(-18.0));
}

}  // namespace
}  // namespace owsim
