#pragma once
// A crash-safe output file (DESIGN.md "nothing half-written is left behind", INTERFACE.md "No
// command leaves a partial output file under its final name").
//
// Bytes go to `<final>.partial` in the same directory; commit() flushes, optionally fsyncs, closes
// and renames it over the final name (an atomic replace on POSIX file systems), then fsyncs the
// directory. If the object is destroyed without commit() — an exception, a crash of the writer
// loop — the temporary is removed and an existing file under the final name is left untouched.
// Every failure (cannot create, disk full on write/flush/close, rename) throws owsim::Error whose
// message starts with the final path. Not thread-safe: one writer per file.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string_view>

namespace owsim {

struct AtomicOutputOptions {
  bool sync_on_commit = true;  // fsync the file before the rename and the directory after it
};

class AtomicOutputFile {
 public:
  // Creates (or truncates) `<final_path>.partial`. The directory must exist.
  explicit AtomicOutputFile(std::filesystem::path final_path, AtomicOutputOptions options = {});
  AtomicOutputFile(AtomicOutputFile&& other) noexcept;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  // Removes the temporary unless commit() succeeded. Never throws.
  ~AtomicOutputFile();

  void write(const void* data, std::size_t size);
  void write(std::string_view text);
  // Overwrites bytes already written (e.g. a header whose counts are known only at the end);
  // [offset, offset + size) must lie within bytes_written(). Later write() calls still append.
  void write_at(std::uint64_t offset, const void* data, std::size_t size);
  // Makes the file appear under its final name, complete. Nothing may be written afterwards.
  void commit();

  [[nodiscard]] const std::filesystem::path& final_path() const { return final_path_; }
  [[nodiscard]] const std::filesystem::path& partial_path() const { return partial_path_; }
  [[nodiscard]] std::uint64_t bytes_written() const { return bytes_written_; }
  [[nodiscard]] bool committed() const { return committed_; }

  // `<final_path>.partial`: where the bytes live until commit().
  [[nodiscard]] static std::filesystem::path partial_path_for(
      const std::filesystem::path& final_path);

 private:
  [[noreturn]] void fail(std::string_view what, int error_number) const;
  void require_open(std::string_view operation) const;

  std::filesystem::path final_path_;
  std::filesystem::path partial_path_;
  AtomicOutputOptions options_;
  std::FILE* file_ = nullptr;
  std::uint64_t bytes_written_ = 0;
  bool committed_ = false;
};

}  // namespace owsim
