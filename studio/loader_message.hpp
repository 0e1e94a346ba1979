#pragma once
// The loader's one-line error ("<file>:<line>: <dotted key path>: <problem>",
// io/scenario/scenario_loader.hpp) taken apart for the studio's forms, so that the message shows
// beside the field its key names: {"message", "line", "key", "problem"}; line and key are absent
// when the message has none (a trajectory file's own error, a file that cannot be read).
#include <nlohmann/json.hpp>
#include <string_view>

namespace owsim::studio {

[[nodiscard]] nlohmann::json loader_message(std::string_view message, std::string_view file);

}  // namespace owsim::studio
