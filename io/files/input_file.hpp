#pragma once
// What every reader of owsim's input files checks before it reads (issue 17): the path names a
// regular file, through any symbolic links (a FIFO would block, a device or /dev/zero would never
// end, a directory or a symlink loop cannot be read), of at most the size a file of its kind can
// hold, so nothing is reserved or slurped from what the file merely claims. Failures are one
// owsim::FileError line, "<path>: cannot read the <what>: <reason>".
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace owsim {

// Sizes no real input of the kind reaches (bytes).
inline constexpr std::uintmax_t kMaxScenarioBytes = std::uintmax_t{16} << 20;    // 16 MiB
inline constexpr std::uintmax_t kMaxTrajectoryBytes = std::uintmax_t{2} << 30;   // 2 GiB
inline constexpr std::uintmax_t kMaxTerrainGridBytes = std::uintmax_t{2} << 30;  // 2 GiB
inline constexpr std::uintmax_t kMaxCheckpointBytes = std::uintmax_t{256} << 20;

// The file's size, after checking that `path` is a regular file (symlinks followed) of at most
// `max_bytes` (0: any size). `what` names the kind of file in messages ("scenario file").
std::uintmax_t require_input_file(const std::filesystem::path& path, std::string_view what,
                                  std::uintmax_t max_bytes = 0);

// The whole file as bytes, after require_input_file.
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                                          std::uintmax_t max_bytes);

}  // namespace owsim
