#pragma once
// Streaming reader and writer of the sensor's word files (SENSOR-SPEC §8, INTERFACE.md
// `flight.d64` / `flight.hellas`): a headerless sequence of packed words, little-endian whatever
// the host. MilOWS words are 64-bit, HELLAS words 32-bit (its header word is an ordinary word).
//
// Both sides go through a fixed buffer (1 MiB by default), so memory stays flat however long the
// flight. The writer appends to an AtomicOutputFile: nothing appears under the final name until
// commit(); checkpoint() and resume() let an interrupted run continue a file (`owsim run
// --resume`). The reader never loads the file whole and reports a size that is not a whole number
// of words (trailing_bytes) instead of silently dropping the tail. Errors throw owsim::Error
// naming the path.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <vector>

#include "io/files/atomic_output_file.hpp"
#include "io/files/writer_checkpoint.hpp"

namespace owsim {

inline constexpr std::size_t kWordFileBufferBytes = std::size_t{1} << 20;
// How many words a reader of a whole recording takes from WordFileReader::read at a time.
inline constexpr std::size_t kWordReadChunk = std::size_t{1} << 16;

// Word: std::uint64_t (MilOWS) or std::uint32_t (HELLAS).
template <typename Word>
class WordFileWriter {
 public:
  explicit WordFileWriter(std::filesystem::path final_path, AtomicOutputOptions options = {},
                          std::size_t buffer_bytes = kWordFileBufferBytes);

  // Continues the temporary file an interrupted writer left at `from` (bytes after it are cut
  // off). Throws owsim::Error naming the path if the temporary is missing or shorter, or if
  // `from` is not a whole number of words.
  [[nodiscard]] static WordFileWriter resume(std::filesystem::path final_path,
                                             const WriterCheckpoint& from,
                                             AtomicOutputOptions options = {},
                                             std::size_t buffer_bytes = kWordFileBufferBytes);

  void write(Word word);
  void write(std::span<const Word> words);  // e.g. a whole frame at once
  // Counts `words` words as written that another process put into the temporary after the ones
  // written so far (a distributed run).
  void skip(std::uint64_t words);
  // Hands every word written so far to the kernel; where to resume from.
  [[nodiscard]] WriterCheckpoint checkpoint();
  // Flushes the buffer and renames the file to its final name.
  void commit();

  [[nodiscard]] std::uint64_t words_written() const { return words_written_; }
  [[nodiscard]] const std::filesystem::path& path() const { return file_.final_path(); }

 private:
  WordFileWriter(AtomicOutputFile file, std::size_t buffer_bytes, std::uint64_t words_written);
  void flush_buffer();

  AtomicOutputFile file_;
  std::vector<unsigned char> buffer_;
  std::size_t buffered_bytes_ = 0;
  std::uint64_t words_written_ = 0;
};

template <typename Word>
class WordFileReader {
 public:
  // Opens a regular file; its size is taken now. Throws owsim::Error if it cannot be opened.
  explicit WordFileReader(std::filesystem::path path,
                          std::size_t buffer_bytes = kWordFileBufferBytes);
  WordFileReader(const WordFileReader&) = delete;
  WordFileReader& operator=(const WordFileReader&) = delete;
  ~WordFileReader();

  // Fills `words` with the next whole words; returns how many (fewer only at the end, 0 once every
  // whole word has been read). Trailing bytes of an incomplete word are never returned.
  std::size_t read(std::span<Word> words);

  [[nodiscard]] std::uint64_t words_total() const { return file_bytes_ / sizeof(Word); }
  [[nodiscard]] std::uint64_t words_read() const { return words_read_; }
  // Bytes after the last whole word: non-zero means the file was cut inside a word.
  [[nodiscard]] std::size_t trailing_bytes() const { return file_bytes_ % sizeof(Word); }
  [[nodiscard]] std::uint64_t file_bytes() const { return file_bytes_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::uint64_t file_bytes_ = 0;
  std::uint64_t words_read_ = 0;
  std::vector<unsigned char> buffer_;
};

using MilowsWordWriter = WordFileWriter<std::uint64_t>;
using HellasWordWriter = WordFileWriter<std::uint32_t>;
using MilowsWordReader = WordFileReader<std::uint64_t>;
using HellasWordReader = WordFileReader<std::uint32_t>;

extern template class WordFileWriter<std::uint64_t>;
extern template class WordFileWriter<std::uint32_t>;
extern template class WordFileReader<std::uint64_t>;
extern template class WordFileReader<std::uint32_t>;

}  // namespace owsim
