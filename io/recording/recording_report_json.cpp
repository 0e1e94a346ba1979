// The recording report for programs: `owsim info FILE --json`.
#include "io/recording/recording_check.hpp"

namespace owsim {
namespace {

nlohmann::json counter_json(const CounterSummary& c) {
  return {{"valid", c.valid},
          {"timeouts", c.timeouts},
          {"beyond_timeout", c.beyond_timeout},
          {"min", c.min},
          {"q1", c.q1},
          {"median", c.median},
          {"q3", c.q3},
          {"max", c.max}};
}

nlohmann::json issues_json(const std::vector<RecordingIssue>& issues) {
  nlohmann::json list = nlohmann::json::array();
  for (const RecordingIssue& issue : issues) {
    list.push_back({{"word", issue.word},
                    {"kind", to_string(issue.kind)},
                    {"description", issue.description}});
  }
  return list;
}

}  // namespace

nlohmann::json to_json(const RecordingReport& r) {
  const TimeTagSummary& t = r.time;
  nlohmann::json json = {
      {"path", r.path.string()},
      {"format", recording_format_name(r.model)},
      {"model", to_string(r.model)},
      {"file_bytes", r.file_bytes},
      {"word_bytes", r.word_bytes},
      {"words", r.words},
      {"trailing_bytes", r.trailing_bytes},
      {"header_words", r.header_words},
      {"pulses", r.pulses},
      {"complete_frames", r.complete_frames},
      {"lines", r.lines},
      {"pulses_per_frame", r.pulses_per_frame},
      {"fibers_per_line", r.fibers_per_line},
      {"timeout_counts", r.timeout_counts},
      {"partial",
       {{"leading_pulses", r.leading_partial_pulses},
        {"trailing_pulses", r.trailing_partial_pulses}}},
      {"returns", r.returns},
      {"second_returns", r.second_returns},
      {"returns_per_fiber", r.returns_per_fiber},
      {"second_returns_per_fiber", r.second_returns_per_fiber},
      {"counter1", counter_json(r.counter1)},
      {"counter2", r.counter2 ? counter_json(*r.counter2) : nlohmann::json(nullptr)},
      {"reference_counter", counter_json(r.reference_counter)},
      {"time",
       {{"tick_s", t.tick_s},
        {"modulus", t.modulus},
        {"first_tag", t.first_tag},
        {"last_tag", t.last_tag},
        {"wraps", t.wraps},
        {"span_ticks", t.span_ticks},
        {"span_s", t.span_s},
        {"pulses_span_s", t.pulses_span_s}}},
      {"encoder", nullptr},
      {"header", nullptr},
      {"ni_marks",
       r.model == SensorModel::hellas ? nlohmann::json(r.ni_marks) : nlohmann::json(nullptr)},
      {"ok", r.sound()},
      {"problem_count", r.problem_count},
      {"problem_counts", r.problem_counts},
      {"problems", issues_json(r.problems)},
      {"note_count", r.note_count},
      {"notes", issues_json(r.notes)},
  };
  if (r.encoder) {
    json["encoder"] = {{"min_counts", r.encoder->min_counts},
                       {"max_counts", r.encoder->max_counts},
                       {"mirror_beta_min_deg", r.encoder->mirror_beta_min_deg},
                       {"mirror_beta_max_deg", r.encoder->mirror_beta_max_deg}};
  }
  if (r.header) {
    json["header"] = {{"beta_code", r.header->beta_code},
                      {"mirror_beta_deg", r.header->mirror_beta_deg}};
  }
  return json;
}

}  // namespace owsim
