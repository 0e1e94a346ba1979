// The recording report for people: `owsim info FILE`.
#include <cstdio>
#include <string>

#include "io/recording/recording_check.hpp"

namespace owsim {
namespace {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string row(const char* label, const std::string& value) {
  std::string line = "  ";
  line += label;
  line.append(line.size() < 20 ? 20 - line.size() : 1, ' ');
  return line + value + '\n';
}

std::string counter_line(const CounterSummary& c, std::uint16_t timeout) {
  std::string text = std::to_string(c.valid) + " returns";
  if (c.valid > 0) {
    text += ": min " + std::to_string(c.min) + ", quartiles " + std::to_string(c.q1) + " / " +
            std::to_string(c.median) + " / " + std::to_string(c.q3) + ", max " +
            std::to_string(c.max);
  }
  text += "; " + std::to_string(c.timeouts) + " timeouts (" + std::to_string(timeout) + ")";
  if (c.beyond_timeout > 0) text += "; " + std::to_string(c.beyond_timeout) + " beyond the timeout";
  return text;
}

std::string fiber_table(const std::vector<std::uint64_t>& per_fiber) {
  constexpr std::size_t kPerRow = 16;
  std::string text;
  for (std::size_t first = 0; first < per_fiber.size(); first += kPerRow) {
    const std::size_t last = std::min(per_fiber.size(), first + kPerRow);
    char label[32];
    std::snprintf(label, sizeof label, "    %3zu-%-3zu ", first + 1, last);
    text += label;
    for (std::size_t i = first; i < last; ++i) {
      char value[32];
      std::snprintf(value, sizeof value, " %6llu", static_cast<unsigned long long>(per_fiber[i]));
      text += value;
    }
    text += '\n';
  }
  return text;
}

std::string issue_list(const char* title, const std::vector<RecordingIssue>& issues,
                       std::uint64_t count) {
  if (count == 0) return std::string(title) + ": none\n";
  std::string text = std::string(title) + ": " + std::to_string(count);
  if (issues.size() < count) text += " (the first " + std::to_string(issues.size()) + " listed)";
  text += '\n';
  for (const RecordingIssue& issue : issues) {
    text += "  word " + std::to_string(issue.word) + ": " + issue.description + " [" +
            std::string(to_string(issue.kind)) + "]\n";
  }
  if (issues.size() < count)
    text += "  ... and " + std::to_string(count - issues.size()) + " more\n";
  return text;
}

}  // namespace

std::string render_text(const RecordingReport& r) {
  const bool milows = r.model == SensorModel::milows;
  std::string text = r.path.string() + ": " + (milows ? "MilOWS" : "HELLAS") + " recording (" +
                     std::string(recording_format_name(r.model)) + "), " +
                     std::to_string(r.file_bytes) + " bytes, " + std::to_string(r.words) +
                     " words of " + std::to_string(r.word_bytes) + " bytes";
  if (r.trailing_bytes > 0) text += " + " + std::to_string(r.trailing_bytes) + " trailing bytes";
  text += '\n';
  text += row("pulses", std::to_string(r.pulses));
  text += row("frames", std::to_string(r.complete_frames) + " complete frames of " +
                            std::to_string(r.pulses_per_frame) + " pulses");
  text += row("lines", std::to_string(r.lines) + " lines (" + std::to_string(r.fibers_per_line) +
                           " pulses each expected)");
  text += row("partial frames",
              std::to_string(r.leading_partial_pulses) + " pulses before the first frame start, " +
                  std::to_string(r.trailing_partial_pulses) + " after the last frame gate");
  const TimeTagSummary& t = r.time;
  text += row("time tags", std::to_string(t.first_tag) + " → " + std::to_string(t.last_tag) + " (" +
                               fixed(t.tick_s * 1e6, 0) + " µs ticks, " + std::to_string(t.wraps) +
                               " wraps): span " + fixed(t.span_s, 4) + " s; pulses / PRF " +
                               fixed(t.pulses_span_s, 4) + " s");
  if (r.encoder) {
    text += row("encoder", std::to_string(r.encoder->min_counts) + " .. " +
                               std::to_string(r.encoder->max_counts) + " counts = mirror β " +
                               fixed(r.encoder->mirror_beta_min_deg, 3) + "° .. " +
                               fixed(r.encoder->mirror_beta_max_deg, 3) + "°");
  }
  if (r.header) {
    text += row("header", "β code " + std::to_string(r.header->beta_code) + " = mirror β " +
                              fixed(r.header->mirror_beta_deg, 2) + "°");
  }
  if (!milows) text += row("NI marks", std::to_string(r.ni_marks));
  text += row(milows ? "counter 1" : "counter", counter_line(r.counter1, r.timeout_counts));
  if (r.counter2) text += row("counter 2", counter_line(*r.counter2, r.timeout_counts));
  text += row("reference fiber", counter_line(r.reference_counter, r.timeout_counts));
  text += "  returns per fiber (" + std::string(milows ? "counter 1" : "counter") +
          " below the timeout; the last fiber is the reference):\n";
  text += fiber_table(r.returns_per_fiber);
  if (r.second_returns > 0) {
    text += "  second returns per fiber (counter 2 below the timeout):\n";
    text += fiber_table(r.second_returns_per_fiber);
  }
  text += issue_list("problems", r.problems, r.problem_count);
  text += issue_list("notes", r.notes, r.note_count);
  return text;
}

}  // namespace owsim
