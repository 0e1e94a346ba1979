#include "io/files/atomic_output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/output_open.hpp"

namespace owsim {
namespace {

// Makes a completed rename durable; best effort (some file systems cannot fsync a directory).
void sync_directory(const std::filesystem::path& directory) {
  const std::filesystem::path dir = directory.empty() ? std::filesystem::path(".") : directory;
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::filesystem::path AtomicOutputFile::partial_path_for(const std::filesystem::path& final_path) {
  std::filesystem::path partial = final_path;
  partial += ".partial";
  return partial;
}

AtomicOutputFile::AtomicOutputFile(std::filesystem::path final_path, AtomicOutputOptions options)
    : final_path_(std::move(final_path)),
      partial_path_(partial_path_for(final_path_)),
      options_(options) {
  if (final_path_.empty()) throw Error("output file: empty path");
  const int fd = create_output_file(partial_path_, final_path_.string());
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int error_number = errno;
    ::close(fd);
    ::unlink(partial_path_.c_str());
    fail("cannot create " + partial_path_.string(), error_number);
  }
}

AtomicOutputFile::AtomicOutputFile(Adopt, std::filesystem::path final_path,
                                   AtomicOutputOptions options)
    : final_path_(std::move(final_path)),
      partial_path_(partial_path_for(final_path_)),
      options_(options),
      committed_(true) {}  // until the temporary is adopted, it is not this object's to remove

AtomicOutputFile AtomicOutputFile::resume(std::filesystem::path final_path, std::uint64_t bytes,
                                          AtomicOutputOptions options) {
  AtomicOutputFile file(Adopt{}, std::move(final_path), options);
  if (file.final_path_.empty()) throw Error("output file: empty path");
  const int fd = open_resumable(file.final_path_, bytes);
  file.resumed_ = true;
  if (::ftruncate(fd, static_cast<off_t>(bytes)) != 0 ||
      (file.file_ = ::fdopen(fd, "r+b")) == nullptr) {
    const int error_number = errno;
    ::close(fd);
    file.fail("cannot resume from " + file.partial_path_.string(), error_number);
  }
  if (::fseeko(file.file_, 0, SEEK_END) != 0) {
    file.fail("cannot resume from " + file.partial_path_.string(), errno);
  }
  file.bytes_written_ = bytes;
  file.written_back_ = bytes;
  file.committed_ = false;
  return file;
}

void AtomicOutputFile::require_resumable(const std::filesystem::path& final_path,
                                         std::uint64_t bytes) {
  ::close(open_resumable(final_path, bytes));
}

int AtomicOutputFile::open_resumable(const std::filesystem::path& final_path, std::uint64_t bytes) {
  const std::filesystem::path partial = partial_path_for(final_path);
  const int fd = open_output_file(partial, O_RDWR, final_path.string(), "cannot resume from");
  struct stat status {};
  if (::fstat(fd, &status) != 0) {
    const int error_number = errno;
    ::close(fd);
    throw file_error(final_path.string(),
                     "cannot resume from " + partial.string() + ": " + std::strerror(error_number));
  }
  const auto size = static_cast<std::uint64_t>(status.st_size);
  if (size < bytes) {
    ::close(fd);
    throw file_error(final_path.string(), "cannot resume: " + partial.string() + " holds " +
                                              std::to_string(size) + " bytes, the checkpoint " +
                                              std::to_string(bytes));
  }
  return fd;
}

AtomicOutputFile::AtomicOutputFile(AtomicOutputFile&& other) noexcept
    : final_path_(std::move(other.final_path_)),
      partial_path_(std::move(other.partial_path_)),
      options_(other.options_),
      file_(std::exchange(other.file_, nullptr)),
      bytes_written_(other.bytes_written_),
      written_back_(other.written_back_),
      committed_(std::exchange(other.committed_, true)),  // the moved-from object owns nothing
      resumed_(other.resumed_) {}

AtomicOutputFile::~AtomicOutputFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_ && !resumed_) {
    std::error_code ignored;
    std::filesystem::remove(partial_path_, ignored);
  }
}

void AtomicOutputFile::fail(std::string_view what, int error_number) const {
  std::string problem(what);
  if (error_number != 0) {
    problem += ": ";
    problem += std::strerror(error_number);
  }
  throw file_error(final_path_.string(), problem);
}

void AtomicOutputFile::require_open(std::string_view operation) const {
  if (file_ == nullptr) {
    fail(std::string(operation) + (committed_ ? " after commit" : " on a closed file"), 0);
  }
}

void AtomicOutputFile::write(const void* data, std::size_t size) {
  require_open("write");
  if (size == 0) return;
  errno = 0;
  if (std::fwrite(data, 1, size, file_) != size) {
    fail("cannot write " + partial_path_.string(), errno);
  }
  bytes_written_ += size;
  if (options_.sync_on_commit && bytes_written_ - written_back_ >= kWritebackStep) {
    start_writeback();
  }
}

void AtomicOutputFile::start_writeback() {
  written_back_ = bytes_written_;
  errno = 0;
  if (std::fflush(file_) != 0) fail("cannot write " + partial_path_.string(), errno);
  // Asynchronous: the kernel starts writing the dirty pages and returns; a file system without
  // it (EINVAL, ESPIPE) simply leaves them all to commit()'s fsync, as before.
  ::sync_file_range(::fileno(file_), 0, 0, SYNC_FILE_RANGE_WRITE);
}

void AtomicOutputFile::write(std::string_view text) { write(text.data(), text.size()); }

void AtomicOutputFile::write_at(std::uint64_t offset, const void* data, std::size_t size) {
  require_open("write");
  if (offset > bytes_written_ || size > bytes_written_ - offset) {
    fail("overwrite of bytes " + std::to_string(offset) + ".." + std::to_string(offset + size) +
             " beyond the " + std::to_string(bytes_written_) + " bytes written",
         0);
  }
  if (size == 0) return;
  errno = 0;
  if (std::fflush(file_) != 0 || ::fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0 ||
      std::fwrite(data, 1, size, file_) != size || std::fflush(file_) != 0 ||
      ::fseeko(file_, 0, SEEK_END) != 0) {
    fail("cannot write " + partial_path_.string(), errno);
  }
}

void AtomicOutputFile::skip(std::uint64_t size) {
  require_open("write");
  errno = 0;
  if (std::fflush(file_) != 0 ||
      ::fseeko(file_, static_cast<off_t>(bytes_written_ + size), SEEK_SET) != 0) {
    fail("cannot write " + partial_path_.string(), errno);
  }
  bytes_written_ += size;
}

void AtomicOutputFile::flush() {
  require_open("flush");
  errno = 0;
  if (std::fflush(file_) != 0) fail("cannot write " + partial_path_.string(), errno);
}

void AtomicOutputFile::commit() {
  require_open("commit");
  errno = 0;
  if (std::fflush(file_) != 0) fail("cannot write " + partial_path_.string(), errno);
  if (options_.sync_on_commit && ::fsync(::fileno(file_)) != 0) {
    fail("cannot sync " + partial_path_.string(), errno);
  }
  std::FILE* file = std::exchange(file_, nullptr);
  errno = 0;
  if (std::fclose(file) != 0) fail("cannot close " + partial_path_.string(), errno);
  if (std::rename(partial_path_.c_str(), final_path_.c_str()) != 0) {
    fail("cannot rename " + partial_path_.string() + " to the final name", errno);
  }
  committed_ = true;
  if (options_.sync_on_commit) sync_directory(final_path_.parent_path());
}

}  // namespace owsim
