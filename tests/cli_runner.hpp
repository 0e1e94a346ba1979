#pragma once
// Runs the built `owsim` (OWSIM_CLI_PATH) for the end-to-end tests: the arguments are passed as
// they are (no shell, so no quoting), the working directory is a fresh temporary folder, and the
// exit status, stdout and stderr come back whole. Test code only.
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace owsim::test {

// A folder under the system's temporary directory, removed with everything in it on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "owsim_test") {
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "_XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("cannot create a temporary folder from " + pattern);
    }
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
    return path_ / name;
  }

 private:
  std::filesystem::path path_;
};

struct CliResult {
  int exit_status = -1;  // the process's exit code; -1 if it did not exit normally
  std::string out;       // everything written to stdout
  std::string err;       // everything written to stderr
  std::string command;   // the arguments joined by spaces, for failure messages
};

inline std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// Runs `program arguments…` with `work_dir` as its working directory (relative paths in the
// arguments are relative to it). stdout and stderr are captured through files in a temporary
// folder, so a large output cannot block the child.
inline CliResult run_program(const std::string& program, const std::vector<std::string>& arguments,
                             const std::filesystem::path& work_dir) {
  CliResult result;
  result.command = program;
  for (const std::string& argument : arguments) result.command += " " + argument;

  const TempDir capture("owsim_cli_capture");
  const std::string out_path = (capture / "stdout").string();
  const std::string err_path = (capture / "stderr").string();
  std::vector<std::string> argv_text = {program};
  argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& text : argv_text) argv.push_back(text.data());
  argv.push_back(nullptr);

  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed for " + result.command);
  if (child == 0) {
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || err < 0 || ::dup2(out, STDOUT_FILENO) < 0 || ::dup2(err, STDERR_FILENO) < 0 ||
        ::chdir(work_dir.c_str()) != 0) {
      ::_exit(126);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("waitpid failed for " + result.command);
  }
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_whole_file(out_path);
  result.err = read_whole_file(err_path);
  return result;
}

// The built `owsim` (OWSIM_CLI_PATH), as run_program.
inline CliResult run_cli(const std::vector<std::string>& arguments,
                         const std::filesystem::path& work_dir) {
  return run_program(OWSIM_CLI_PATH, arguments, work_dir);
}

inline CliResult run_cli(std::initializer_list<std::string> arguments,
                         const std::filesystem::path& work_dir) {
  return run_cli(std::vector<std::string>(arguments), work_dir);
}

}  // namespace owsim::test
