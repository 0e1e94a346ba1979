// `owsim pattern`: one frame's pulse table as CSV on stdout (INTERFACE.md "owsim pattern columns"),
// with the scenario-free defaults of SENSOR-SPEC and the frame jitter drawn from --seed.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "geometry/error.hpp"
#include "sensor/scan_params.hpp"
#include "sensor/scan_params_check.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim::cli {
namespace {

struct PatternOptions {
  std::string sensor = "milows";
  std::int64_t frame = 0;
  std::uint64_t seed = 0;
};

// An angle as printed: six decimals, and no "-0.000000" for a value that rounds to zero.
double printable_deg(double angle_deg) { return std::abs(angle_deg) < 5e-7 ? 0.0 : angle_deg; }

void flush(fmt::memory_buffer& buffer) {
  if (std::fwrite(buffer.data(), 1, buffer.size(), stdout) != buffer.size()) {
    throw Error("stdout: write failed");
  }
  buffer.clear();
}

void write_pattern(const PatternOptions& options) {
  ScanParams params;
  params.model = parse_sensor_model(options.sensor).value_or(SensorModel::milows);
  validate(params);
  const FrameSweep sweep = frame_sweep(params, options.seed, options.frame);
  const bool has_encoder = params.model == SensorModel::milows;

  fmt::memory_buffer buffer;
  fmt::format_to(std::back_inserter(buffer),
                 "pulse,line,fiber,time_s,alpha_deg,beta_deg,encoder,fg,lg,movdir\n");
  const int pulses = params.pulses_per_frame();
  for (int k = 0; k < pulses; ++k) {
    const Pulse pulse = pulse_of_frame(params, sweep, k);
    auto out = fmt::format_to(std::back_inserter(buffer), "{},{},{},{:.9f},", pulse.index,
                              pulse.line, pulse.fiber, pulse.time_s);
    if (!pulse.reference) out = fmt::format_to(out, "{:.6f}", printable_deg(pulse.alpha_deg));
    out = fmt::format_to(out, ",{:.6f},", printable_deg(pulse.beta_deg));
    if (has_encoder) out = fmt::format_to(out, "{}", pulse.encoder);
    fmt::format_to(out, ",{:d},{:d},{}\n", pulse.frame_gate ? 1 : 0, pulse.line_gate ? 1 : 0,
                   pulse.mov_dir);
    if (buffer.size() > 1 << 16) flush(buffer);
  }
  flush(buffer);
  if (std::fflush(stdout) != 0) throw Error("stdout: write failed");
}

}  // namespace

void add_pattern_command(CLI::App& app, CommandResult&) {
  // CLI11 would read "-4" into an unsigned frame index as 2^64 − 4: refuse a sign.
  const CLI::Validator kNonNegative(
      [](const std::string& text) {
        return text.starts_with('-') ? std::string("must be ≥ 0") : std::string();
      },
      "NONNEGATIVE");
  auto options = std::make_shared<PatternOptions>();
  CLI::App* command = app.add_subcommand("pattern", "one frame's pulse table as CSV on stdout");
  command->add_option("--sensor", options->sensor, "sensor model: milows or hellas")
      ->check(CLI::IsMember({"milows", "hellas"}))
      ->capture_default_str();
  command->add_option("--frame", options->frame, "frame index K (0 sweeps upward from −18°)")
      ->check(kNonNegative)
      ->capture_default_str();
  command->add_option("--seed", options->seed, "seed of the frame-start jitter")
      ->check(seed_number())
      ->capture_default_str();
  command->callback([options] { write_pattern(*options); });
}

}  // namespace owsim::cli
