#include "io/recording/word_file.hpp"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/little_endian.hpp"

namespace owsim {
namespace {

// A buffer holding a whole number of words, at least one.
template <typename Word>
std::size_t whole_words_bytes(std::size_t buffer_bytes) {
  return std::max<std::size_t>(1, buffer_bytes / sizeof(Word)) * sizeof(Word);
}

std::string with_reason(std::string problem, int error_number) {
  if (error_number != 0) {
    problem += ": ";
    problem += std::strerror(error_number);
  }
  return problem;
}

}  // namespace

template <typename Word>
WordFileWriter<Word>::WordFileWriter(std::filesystem::path final_path, AtomicOutputOptions options,
                                     std::size_t buffer_bytes)
    : file_(std::move(final_path), options), buffer_(whole_words_bytes<Word>(buffer_bytes)) {}

template <typename Word>
WordFileWriter<Word>::WordFileWriter(AtomicOutputFile file, std::size_t buffer_bytes,
                                     std::uint64_t words_written)
    : file_(std::move(file)),
      buffer_(whole_words_bytes<Word>(buffer_bytes)),
      words_written_(words_written) {}

template <typename Word>
WordFileWriter<Word> WordFileWriter<Word>::resume(std::filesystem::path final_path,
                                                  const WriterCheckpoint& from,
                                                  AtomicOutputOptions options,
                                                  std::size_t buffer_bytes) {
  if (from.file_bytes != from.records * sizeof(Word)) {
    throw input_error(final_path.string(), "cannot resume: the checkpoint's " +
                                               std::to_string(from.file_bytes) + " bytes are not " +
                                               std::to_string(from.records) + " words");
  }
  return WordFileWriter(AtomicOutputFile::resume(std::move(final_path), from.file_bytes, options),
                        buffer_bytes, from.records);
}

template <typename Word>
void WordFileWriter<Word>::write(Word word) {
  write(std::span<const Word>(&word, 1));
}

template <typename Word>
void WordFileWriter<Word>::write(std::span<const Word> words) {
  // As many words as the buffer has room for at a time: one copy on a little-endian host.
  while (!words.empty()) {
    if (buffered_bytes_ == buffer_.size()) flush_buffer();
    const std::size_t n = std::min(words.size(), (buffer_.size() - buffered_bytes_) / sizeof(Word));
    unsigned char* const out = buffer_.data() + buffered_bytes_;
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(out, words.data(), n * sizeof(Word));
    } else {
      for (std::size_t i = 0; i < n; ++i) store_little_endian(words[i], out + i * sizeof(Word));
    }
    buffered_bytes_ += n * sizeof(Word);
    words_written_ += n;
    words = words.subspan(n);
  }
}

template <typename Word>
void WordFileWriter<Word>::flush_buffer() {
  file_.write(buffer_.data(), buffered_bytes_);
  buffered_bytes_ = 0;
}

template <typename Word>
void WordFileWriter<Word>::skip(std::uint64_t words) {
  flush_buffer();
  file_.skip(words * sizeof(Word));
  words_written_ += words;
}

template <typename Word>
WriterCheckpoint WordFileWriter<Word>::checkpoint() {
  flush_buffer();
  file_.flush();
  return {file_.bytes_written(), words_written_};
}

template <typename Word>
void WordFileWriter<Word>::commit() {
  flush_buffer();
  file_.commit();
}

template <typename Word>
WordFileReader<Word>::WordFileReader(std::filesystem::path path, std::size_t buffer_bytes)
    : path_(std::move(path)), buffer_(whole_words_bytes<Word>(buffer_bytes)) {
  std::error_code error;
  const auto status = std::filesystem::status(path_, error);
  if (error) throw file_error(path_.string(), with_reason("cannot open", error.value()));
  if (!std::filesystem::is_regular_file(status)) {
    throw file_error(path_.string(), "cannot open: not a regular file");
  }
  file_bytes_ = std::filesystem::file_size(path_, error);
  if (error) throw file_error(path_.string(), with_reason("cannot open", error.value()));
  file_ = std::fopen(path_.c_str(), "rb");
  if (file_ == nullptr) throw file_error(path_.string(), with_reason("cannot open", errno));
}

template <typename Word>
WordFileReader<Word>::~WordFileReader() {
  if (file_ != nullptr) std::fclose(file_);
}

template <typename Word>
std::size_t WordFileReader<Word>::read(std::span<Word> words) {
  const std::uint64_t left = words_total() - words_read_;
  const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(words.size(), left));
  const std::size_t words_per_buffer = buffer_.size() / sizeof(Word);
  for (std::size_t done = 0; done < count;) {
    const std::size_t chunk = std::min(count - done, words_per_buffer);
    errno = 0;
    const std::size_t got = std::fread(buffer_.data(), sizeof(Word), chunk, file_);
    if (got != chunk) {
      if (std::ferror(file_) != 0)
        throw input_error(path_.string(), with_reason("read error", errno));
      throw input_error(path_.string(), "file shrank while being read (ends after word " +
                                            std::to_string(words_read_ + done + got) + ")");
    }
    for (std::size_t i = 0; i < chunk; ++i) {
      words[done + i] = load_little_endian<Word>(buffer_.data() + i * sizeof(Word));
    }
    done += chunk;
  }
  words_read_ += count;
  return count;
}

template class WordFileWriter<std::uint64_t>;
template class WordFileWriter<std::uint32_t>;
template class WordFileReader<std::uint64_t>;
template class WordFileReader<std::uint32_t>;

}  // namespace owsim
