#include "studio/loader_message.hpp"

#include <cctype>
#include <string>

namespace owsim::studio {
namespace {

// A dotted key path of the scenario: names, dots and [index] parts, no spaces.
bool is_key_path(std::string_view text) {
  if (text.empty()) return false;
  for (const char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_' && c != '.' && c != '[' &&
        c != ']') {
      return false;
    }
  }
  return true;
}

}  // namespace

nlohmann::json loader_message(std::string_view message, std::string_view file) {
  nlohmann::json out = {{"message", std::string(message)}};
  std::string_view rest = message;
  if (!file.empty() && rest.starts_with(file) && rest.substr(file.size()).starts_with(":")) {
    rest.remove_prefix(file.size() + 1);
  } else {
    return out;
  }
  std::size_t digits = 0;
  while (digits < rest.size() && std::isdigit(static_cast<unsigned char>(rest[digits])) != 0) {
    ++digits;
  }
  if (digits > 0 && rest.substr(digits).starts_with(": ")) {
    out["line"] = std::stoll(std::string(rest.substr(0, digits)));
    rest.remove_prefix(digits + 2);
  } else if (rest.starts_with(" ")) {
    rest.remove_prefix(1);
  }
  const std::size_t colon = rest.find(": ");
  if (colon != std::string_view::npos && is_key_path(rest.substr(0, colon))) {
    out["key"] = std::string(rest.substr(0, colon));
    rest.remove_prefix(colon + 2);
  }
  out["problem"] = std::string(rest);
  return out;
}

}  // namespace owsim::studio
