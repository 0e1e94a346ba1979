#pragma once
// The fuzzers' input as a file: the readers under test take a path, so each input is written to
// one temporary file per fuzzing process (named by its pid, so parallel jobs do not collide) and
// read back from there. Fuzz code only.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace owsim::fuzz {

// Writes the bytes to <temp dir>/owsim_fuzz_<pid><extension> and returns its path. Aborts if it
// cannot: a fuzzer that silently reads nothing would report clean runs.
inline std::string write_input_file(const std::uint8_t* data, std::size_t size,
                                    const std::string& extension) {
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("owsim_fuzz_" + std::to_string(::getpid()) + extension))
                                      .string();
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  if (std::fclose(file) != 0) std::abort();
  return path;
}

}  // namespace owsim::fuzz
