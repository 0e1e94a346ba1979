#pragma once
// Benchmarks that measure whole `owsim` processes (bench_flight_memory, bench_process_start):
// the program to run, a scratch folder, and one child process run to its end with its wall time
// and peak resident set.
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace owsim::bench {

namespace fs = std::filesystem;

// The repository (this file's folder's parent).
inline fs::path source_dir() { return fs::path(__FILE__).parent_path().parent_path(); }

// The `owsim` to run: $OWSIM_CLI, else the build's own (../owsim beside this program's folder).
inline fs::path owsim_program() {
  if (const char* chosen = std::getenv("OWSIM_CLI"); chosen != nullptr && *chosen) return chosen;
  const fs::path beside = fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "owsim";
  if (!fs::exists(beside)) {
    throw std::runtime_error(beside.string() + " not found: build owsim_cli or set OWSIM_CLI");
  }
  return beside;
}

// A fresh folder under the system's temporary directory, removed with its contents at the end.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "owsim_bench_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp " + pattern);
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

struct ChildRun {
  int exit_status = -1;
  double peak_rss_mb = 0.0;
  double wall_s = 0.0;
};

// Runs the program with `arguments`, stdout to /dev/null; its exit status, peak RSS and wall time
// from fork to reaped exit.
inline ChildRun run_child(const fs::path& program, const std::vector<std::string>& arguments) {
  std::vector<std::string> text = {program.string()};
  text.insert(text.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& item : text) argv.push_back(item.data());
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    if (std::freopen("/dev/null", "w", stdout) == nullptr) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  while (::wait4(child, &status, 0, &usage) < 0) {
    if (errno != EINTR) throw std::runtime_error("wait4 failed");
  }
  ChildRun run;
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: KiB
  return run;
}

}  // namespace owsim::bench
