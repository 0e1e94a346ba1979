#include "io/files/input_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "geometry/error.hpp"

namespace owsim {
namespace {

std::string size_text(std::uintmax_t bytes) {
  if (bytes >= (std::uintmax_t{1} << 30) && bytes % (std::uintmax_t{1} << 30) == 0) {
    return std::to_string(bytes >> 30) + " GiB";
  }
  if (bytes >= (std::uintmax_t{1} << 20) && bytes % (std::uintmax_t{1} << 20) == 0) {
    return std::to_string(bytes >> 20) + " MiB";
  }
  return std::to_string(bytes) + " bytes";
}

const char* kind_of(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory:
      return "a directory";
    case std::filesystem::file_type::fifo:
      return "a FIFO";
    case std::filesystem::file_type::socket:
      return "a socket";
    case std::filesystem::file_type::block:
    case std::filesystem::file_type::character:
      return "a device";
    default:
      return "not a regular file";
  }
}

}  // namespace

std::uintmax_t require_input_file(const std::filesystem::path& path, std::string_view what,
                                  std::uintmax_t max_bytes) {
  const std::string cannot = "cannot read the " + std::string(what) + ": ";
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error) {
    const bool missing = error == std::errc::no_such_file_or_directory;
    throw file_error(path.string(), cannot + (missing ? "no such file" : error.message()));
  }
  if (status.type() == std::filesystem::file_type::not_found) {
    throw file_error(path.string(), cannot + "no such file");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw file_error(path.string(),
                     cannot + "it is " + kind_of(status.type()) + ", not a regular file");
  }
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  if (error) throw file_error(path.string(), cannot + error.message());
  if (max_bytes > 0 && bytes > max_bytes) {
    throw file_error(path.string(), cannot + "it holds " + std::to_string(bytes) +
                                        " bytes, more than any " + std::string(what) + " (" +
                                        size_text(max_bytes) + ")");
  }
  return bytes;
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::uintmax_t max_bytes) {
  const std::uintmax_t bytes = require_input_file(path, what, max_bytes);
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  const std::string cannot = "cannot read the " + std::string(what) + ": ";
  if (!file) throw file_error(path.string(), cannot + std::strerror(errno));
  std::string text(static_cast<std::size_t>(bytes), '\0');
  const std::size_t got = std::fread(text.data(), 1, text.size(), file.get());
  if (got != text.size() || std::ferror(file.get()) != 0) {
    throw file_error(path.string(), cannot + "the file changed or could not be read");
  }
  return text;
}

}  // namespace owsim
