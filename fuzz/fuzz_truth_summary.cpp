// libFuzzer target: a run's summary.json and truth.csv as `owsim pd` and `owsim roc` read them, and
// the reports made of them (issue 45). The input is summary.json's text, a NUL byte, then
// truth.csv's. The readers the commands use (evaluation/flight_facts.hpp, truth_table.hpp) take
// the texts in memory; the wires' tracks go through `pd`'s and `roc`'s computations and renderers
// (pd_report.hpp, roc_report.hpp: pd.csv, pd.json, pd.svg, roc.csv, roc.json, roc.svg). Any input
// must either give the reports or throw owsim::Error whose message is one line naming the file; any
// other exception, a crash, a sanitizer report or a message that is not such a line is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "evaluation/pd_report.hpp"
#include "evaluation/roc_report.hpp"
#include "geometry/error.hpp"

namespace {

// A message as the commands print it: one line, naming the file it is about.
void require_one_line_naming_a_file(std::string_view message) {
  if (message.find('\n') != std::string_view::npos) std::abort();
  if (!message.starts_with("summary.json: ") && !message.starts_with("truth.csv")) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  const std::string_view summary = input.substr(0, split);
  const std::string_view truth =
      split == std::string_view::npos ? std::string_view() : input.substr(split + 1);
  static const owsim::PdOptions pd_options;    // every wire pooled, 0:1300:50, K = 1 in W = 1 s
  static const owsim::RocOptions roc_options;  // every wire, 700:800
  static const std::string values[] = {"0.003"};
  try {
    owsim::FlightTracks flight;
    flight.facts = owsim::parse_flight_facts(summary, "summary.json");
    flight.tracks = owsim::parse_truth_csv(truth, "truth.csv", flight.facts,
                                           [](std::string_view id, std::string_view object_class) {
                                             return roc_options.target.matches(id, object_class);
                                           });
    const std::span<const owsim::FlightTracks> flights(&flight, 1);
    const owsim::PdReport pd = owsim::pd_report_of(flights, pd_options);
    for (const owsim::ReportFile& file : owsim::pd_report_files(pd, pd_options)) {
      if (file.text.empty()) std::abort();
    }
    const owsim::RocReport roc = owsim::roc_report_of(flights, values, roc_options);
    for (const owsim::ReportFile& file : owsim::roc_report_files(roc, roc_options)) {
      if (file.text.empty()) std::abort();
    }
  } catch (const owsim::Error& error) {
    require_one_line_naming_a_file(error.what());
  }
  return 0;
}
