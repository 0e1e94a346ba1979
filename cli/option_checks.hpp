#pragma once
// Validators for command-line numbers whose failure is one short line (CLI11's own range checks
// print the whole double range).
#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
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

// A whole number in [0, 2^64 − 1] written as digits: CLI11 alone would read "-1" as 2^64 − 1 and
// 2^64 as 0, so two different seeds would run as one.
inline CLI::Validator seed_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error == std::errc::result_out_of_range) {
          return "must be in [0, 18446744073709551615], got " + text;
        }
        if (error != std::errc() || end != text.data() + text.size()) {
          return "must be a whole number in [0, 18446744073709551615], got '" + text + "'";
        }
        return {};
      },
      "SEED");
}

}  // namespace owsim::cli
