#pragma once
// owsim::Error — the one exception type library code throws. Its message is the single line a
// user sees: "<file>:<line or key>: <problem>" for bad input, or a plain sentence otherwise.
// owsim::FileError, derived from it, says a file or folder could not be opened, read, created or
// written (the input itself may be fine): the C ABI reports it as OWSIM_ERROR_FILE and Python as
// OSError, every other owsim::Error as OWSIM_ERROR_INPUT / ValueError. Only the shells (cli/, the
// C ABI, the Python module) catch them and turn them into a message and an exit or status code.
#include <stdexcept>
#include <string>
#include <string_view>

namespace owsim {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FileError : public Error {
 public:
  using Error::Error;
};

// "<where>: <problem>", where `where` is "file", "file:line" or "file: key" — whatever locates
// the bad input most precisely.
[[nodiscard]] inline Error input_error(std::string_view where, std::string_view problem) {
  std::string message(where);
  message += ": ";
  message += problem;
  return Error(message);
}

// The same for a file that cannot be opened, read, created or written: "<path>: <problem>".
[[nodiscard]] inline FileError file_error(std::string_view path, std::string_view problem) {
  return FileError(input_error(path, problem).what());
}

}  // namespace owsim
