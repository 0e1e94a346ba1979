#pragma once
// Runs a Python oracle (numpy, scipy, pyproj) with OWSIM_PYTHON for the tests that check owsim
// against an independent implementation, and writes C++ numbers as Python literals that read back
// to the same double. Test code only: a script that exits non-zero fails the calling test.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace owsim::test {

struct PythonRun {
  std::string arguments;     // appended to the command line (through the shell)
  bool with_stderr = false;  // return stderr too, interleaved with stdout
};

// Runs the Python file `script_path` and returns what it printed.
inline std::string run_python_file(const std::filesystem::path& script_path,
                                   const PythonRun& run = {}) {
  std::string command = std::string(OWSIM_PYTHON) + " " + script_path.string();
  if (!run.arguments.empty()) command += " " + run.arguments;
  if (run.with_stderr) command += " 2>&1";
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  EXPECT_NE(pipe, nullptr) << command;
  if (pipe == nullptr) return output;
  std::array<char, 4096> chunk{};
  std::size_t read = 0;
  while ((read = std::fread(chunk.data(), 1, chunk.size(), pipe)) > 0)
    output.append(chunk.data(), read);
  EXPECT_EQ(::pclose(pipe), 0) << command << "\n" << output;
  return output;
}

// Runs the Python source `script` (written to a fresh temporary folder) and returns what it
// printed.
inline std::string run_python(const std::string& script, const PythonRun& run = {}) {
  const TempDir folder("owsim_python_oracle");
  const std::filesystem::path path = folder / "oracle.py";
  std::ofstream(path) << script;
  return run_python_file(path, run);
}

// `value` with 17 significant digits: Python reads back the same double.
inline std::string python_number(double value) {
  std::array<char, 40> text{};
  std::snprintf(text.data(), text.size(), "%.17g", value);
  return text.data();
}

// "[v0,v1,…,]", each as python_number.
inline std::string python_list(const std::vector<double>& values) {
  std::string text = "[";
  for (const double value : values) text += python_number(value) + ",";
  return text + "]";
}

// The numbers a script printed separated by white space, in order (reading stops at the first
// word that is not a number).
inline std::vector<double> numbers_printed(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> values;
  double v = 0;
  while (in >> v) values.push_back(v);
  return values;
}

}  // namespace owsim::test
