#include "io/files/output_open.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "geometry/error.hpp"

namespace owsim {
namespace {

[[noreturn]] void fail(std::string_view error_path, std::string_view what,
                       const std::filesystem::path& path, std::string_view reason) {
  throw file_error(error_path,
                   std::string(what) + " " + path.string() + ": " + std::string(reason));
}

// "it is a FIFO", … for what is not a regular file.
std::string kind_of(mode_t mode) {
  if (S_ISLNK(mode)) return "it is a symbolic link (not followed)";
  if (S_ISDIR(mode)) return "it is a directory";
  if (S_ISFIFO(mode)) return "it is a FIFO, not a regular file";
  if (S_ISSOCK(mode)) return "it is a socket, not a regular file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "it is a device, not a regular file";
  return "not a regular file";
}

// Why `path` could not be opened (error_number from open): what sits there, if that is the reason.
std::string open_failure(const std::filesystem::path& path, int error_number) {
  struct stat status {};
  if (::lstat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) {
    return kind_of(status.st_mode);
  }
  return std::strerror(error_number);
}

}  // namespace

void clear_output_name(const std::filesystem::path& path, std::string_view error_path) {
  // unlink removes a link itself, never its target; a directory cannot be unlinked.
  if (::unlink(path.c_str()) == 0 || errno == ENOENT || errno == ENOTDIR) return;
  const int error_number = errno;
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return;  // gone meanwhile; creating it tells the rest
  if (S_ISDIR(status.st_mode)) fail(error_path, "cannot create", path, "it is a directory");
  fail(error_path, "cannot create", path,
       "cannot remove what is there: " + std::string(std::strerror(error_number)));
}

int create_output_file(const std::filesystem::path& path, std::string_view error_path) {
  clear_output_name(path, error_path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) {
    if (errno == EEXIST) {
      fail(error_path, "cannot create", path,
           "something was put in its place while owsim created it (not written through)");
    }
    fail(error_path, "cannot create", path, std::strerror(errno));
  }
  return fd;
}

int open_output_file(const std::filesystem::path& path, int flags, std::string_view error_path,
                     std::string_view what) {
  const int fd = ::open(path.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) fail(error_path, what, path, open_failure(path, errno));
  struct stat status {};
  std::string problem;
  if (::fstat(fd, &status) != 0) {
    problem = std::strerror(errno);
  } else if (!S_ISREG(status.st_mode)) {
    problem = kind_of(status.st_mode);
  } else if (status.st_nlink != 1) {
    problem = "it has " + std::to_string(status.st_nlink) + " names (hard links), not one";
  } else if (status.st_uid != ::geteuid()) {
    problem = "it belongs to another user";
  } else if (const int now = ::fcntl(fd, F_GETFL);
             now == -1 || ::fcntl(fd, F_SETFL, now & ~O_NONBLOCK) != 0) {
    problem = std::strerror(errno);
  }
  if (!problem.empty()) {
    ::close(fd);
    fail(error_path, what, path, problem);
  }
  return fd;
}

void make_output_subfolder(const std::filesystem::path& folder) {
  if (::mkdir(folder.c_str(), 0777) == 0) return;
  const int error_number = errno;
  struct stat status {};
  if (error_number == EEXIST && ::lstat(folder.c_str(), &status) == 0) {
    if (S_ISDIR(status.st_mode)) return;
    throw file_error(folder.string(), "cannot create the folder: " +
                                          (S_ISREG(status.st_mode) ? std::string("it is a file")
                                                                   : kind_of(status.st_mode)));
  }
  throw file_error(folder.string(),
                   std::string("cannot create the folder: ") + std::strerror(error_number));
}

void make_output_subfolders(const std::filesystem::path& base,
                            const std::filesystem::path& relative) {
  std::filesystem::path folder = base;
  for (const std::filesystem::path& name : relative) {
    if (name.empty() || name == "." || name == "..") {
      throw file_error((base / relative).string(), "cannot create the folder: not a plain name");
    }
    folder /= name;
    make_output_subfolder(folder);
  }
}

}  // namespace owsim
