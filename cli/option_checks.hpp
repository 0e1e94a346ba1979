#pragma once
// Validators for command-line numbers whose failure is one short line (CLI11's own range checks
// print the whole double range).
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace owsim::cli {

// A finite number > 0.
inline CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        try {
          std::size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (!(std::isfinite(value) && value > 0.0)) return "must be positive, got " + text;
        return {};
      },
      "POSITIVE");
}

}  // namespace owsim::cli
