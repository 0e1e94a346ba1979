#pragma once
// owsim::Error — the one exception type library code throws. Its message is the single line a
// user sees: "<file>:<line or key>: <problem>" for bad input, or a plain sentence otherwise.
// Only cli/ catches it and turns it into a message and an exit code.
#include <stdexcept>
#include <string>
#include <string_view>

namespace owsim {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "<where>: <problem>", where `where` is "file", "file:line" or "file: key" — whatever locates
// the bad input most precisely.
[[nodiscard]] inline Error input_error(std::string_view where, std::string_view problem) {
  std::string message(where);
  message += ": ";
  message += problem;
  return Error(message);
}

}  // namespace owsim
