// `owsim info FILE [--format d64|hellas] [--json]`: what a recording holds, checked
// (INTERFACE.md). Exit status 0 when the structure is sound, 1 when problems were found.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "io/files/json_text.hpp"
#include "io/recording/recording_check.hpp"

namespace owsim::cli {
namespace {

struct InfoOptions {
  std::string file;
  std::string format;  // empty: from the extension
  bool json = false;
};

void run_info(const InfoOptions& options, CommandResult& result) {
  const std::optional<SensorModel> model = options.format.empty()
                                               ? recording_model_from_extension(options.file)
                                               : parse_recording_format(options.format);
  if (!model) {
    throw input_error(options.file,
                      "unknown recording format (extension .d64 or .hellas expected); "
                      "give --format d64|hellas");
  }
  ScanParams scan;
  scan.model = *model;
  const RecordingReport report = check_recording(options.file, scan);
  if (options.json) {
    std::cout << json_text(to_json(report), 2) << '\n';
  } else {
    std::cout << render_text(report);
  }
  result.exit_status = report.sound() ? 0 : 1;
}

}  // namespace

void add_info_command(CLI::App& app, CommandResult& result) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* info = app.add_subcommand("info", "what a recording holds, checked");
  info->add_option("FILE", options->file, "a MilOWS (.d64) or HELLAS (.hellas) word file")
      ->required();
  info->add_option("--format", options->format, "the word format, when the extension does not say")
      ->check(CLI::IsMember({"d64", "hellas"}));
  info->add_flag("--json", options->json, "print the report as JSON");
  info->footer(
      "Exit status 0 when the recording's structure is sound, 1 when problems were found "
      "(they are listed with their word index).");
  info->callback([options, &result] { run_info(*options, result); });
}

}  // namespace owsim::cli
