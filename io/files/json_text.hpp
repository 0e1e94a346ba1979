#pragma once
// JSON as owsim writes it (summary.json, the run checkpoint, `owsim info --json`, `owsim bench
// --json`): nlohmann::json's dump, except that text which is not valid UTF-8 (a path given in
// Latin-1 on the command line) is written with U+FFFD in place of the bad bytes instead of
// throwing after the other outputs were committed (issue 17). Scenario text is refused earlier,
// at load, when it is not UTF-8 (io/scenario/yaml_reader.hpp).
#include <nlohmann/json.hpp>
#include <string>

namespace owsim {

[[nodiscard]] inline std::string json_text(const nlohmann::json& value, int indent = -1) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace owsim
