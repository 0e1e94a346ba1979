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
//
// A killed process runs no destructor, so its `.partial` survives: resume() adopts it, cut back to
// the size it had at a checkpoint (flush() had handed those bytes to the kernel, which keeps them
// when the process dies), and appends from there (`owsim run --resume`).
//
// The temporary is never opened through what sits at its name (io/files/output_open.hpp): the
// constructor removes whatever is there (a symbolic or hard link, a FIFO, a file; a directory is
// refused) and creates the file new, O_EXCL|O_NOFOLLOW; resume() and the other processes of a
// distributed run reopen it O_NOFOLLOW and accept only a regular file of this user with one name.
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
  // A file synced at commit hands its bytes to the kernel and has it start writing them to the
  // disk, without waiting, each time this many more have been written: commit()'s fsync then
  // waits for the last step's bytes only, and the disk works while the program computes.
  static constexpr std::uint64_t kWritebackStep = std::uint64_t{8} << 20;

  // Creates `<final_path>.partial` new (whatever was at that name is removed first, never
  // followed). The directory must exist.
  explicit AtomicOutputFile(std::filesystem::path final_path, AtomicOutputOptions options = {});
  // Reopens the `<final_path>.partial` an interrupted writer left, cut to its first `bytes` bytes,
  // for appending. Throws owsim::Error naming the final path if the temporary is missing, holds
  // fewer than `bytes` bytes, or is not a regular file of this user with one name (a symbolic
  // link there is not followed).
  // The temporary of a resumed file is never removed by the destructor: a run that fails after
  // resuming leaves it for the next --resume, which cuts it back to the checkpoint again.
  [[nodiscard]] static AtomicOutputFile resume(std::filesystem::path final_path,
                                               std::uint64_t bytes,
                                               AtomicOutputOptions options = {});
  // Throws what resume() would throw for a missing or short temporary, touching nothing: a
  // resume checks every file this way before it cuts any of them back.
  static void require_resumable(const std::filesystem::path& final_path, std::uint64_t bytes);
  AtomicOutputFile(AtomicOutputFile&& other) noexcept;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  // Removes the temporary unless commit() succeeded or the file was resumed. Never throws.
  ~AtomicOutputFile();

  void write(const void* data, std::size_t size);
  void write(std::string_view text);
  // Overwrites bytes already written (e.g. a header whose counts are known only at the end);
  // [offset, offset + size) must lie within bytes_written(). Later write() calls still append.
  void write_at(std::uint64_t offset, const void* data, std::size_t size);
  // Counts the next `size` bytes as written without writing them: another process puts them into
  // the temporary (a distributed run, distributed/run_placement.hpp). Later writes go after them.
  void skip(std::uint64_t size);
  // Hands every byte written so far to the kernel (no fsync): they survive the process being
  // killed, and the temporary then holds exactly bytes_written() bytes.
  void flush();
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
  struct Adopt {};
  AtomicOutputFile(Adopt, std::filesystem::path final_path, AtomicOutputOptions options);
  // The temporary of `final_path` opened read-write after resume()'s checks.
  [[nodiscard]] static int open_resumable(const std::filesystem::path& final_path,
                                          std::uint64_t bytes);
  // Hands what has been written to the kernel and starts its writeback (kWritebackStep).
  void start_writeback();
  [[noreturn]] void fail(std::string_view what, int error_number) const;
  void require_open(std::string_view operation) const;

  std::filesystem::path final_path_;
  std::filesystem::path partial_path_;
  AtomicOutputOptions options_;
  std::FILE* file_ = nullptr;
  std::uint64_t bytes_written_ = 0;
  std::uint64_t written_back_ = 0;  // bytes_written() when writeback was last started
  bool committed_ = false;
  bool resumed_ = false;  // the temporary outlives a failure (resume())
};

}  // namespace owsim
