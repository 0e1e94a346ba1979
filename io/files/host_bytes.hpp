#pragma once
// Values as their own bytes, in the host's byte order and layout, for bytes that only the same
// owsim build reads back: a finished MCAP chunk and the frames a distributed run gathers
// (io/mcap/mcap_chunk.hpp, distributed/placed_frame_bytes.hpp). Not a file format: a file's fixed
// little-endian layout is io/files/binary_record.hpp. Exact: the bytes are copied, never converted.
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "geometry/error.hpp"

namespace owsim {

// Appends the bytes of `value`.
template <typename T>
void put_host_bytes(std::string& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Appends the count of `values` (std::uint64_t), then their bytes.
template <typename T>
void put_host_vector(std::string& out, const std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  put_host_bytes(out, static_cast<std::uint64_t>(values.size()));
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Appends the length of `text` (std::uint64_t), then its bytes.
inline void put_host_text(std::string& out, std::string_view text) {
  put_host_bytes(out, static_cast<std::uint64_t>(text.size()));
  out += text;
}

// Reads back, in the same order, what put_host_bytes, put_host_vector and put_host_text wrote.
// Throws owsim::Error(`end_message`) when the bytes end first; the message names what was read
// ("placed frames: the bytes end inside a frame").
class HostBytesReader {
 public:
  HostBytesReader(std::string_view bytes, std::string end_message)
      : bytes_(bytes), end_message_(std::move(end_message)) {}

  template <typename T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    get_bytes(&value, sizeof value);
  }
  // `values` becomes the count read first, then that many values.
  template <typename T>
  void get_vector(std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t count = 0;
    get(count);
    if (count > bytes_.size() / sizeof(T)) fail();
    values.resize(static_cast<std::size_t>(count));
    get_bytes(values.data(), values.size() * sizeof(T));
  }
  // The length read first, then that many bytes.
  [[nodiscard]] std::string get_text() {
    std::uint64_t size = 0;
    get(size);
    if (size > bytes_.size()) fail();
    std::string text(bytes_.substr(0, static_cast<std::size_t>(size)));
    bytes_.remove_prefix(static_cast<std::size_t>(size));
    return text;
  }
  [[nodiscard]] bool empty() const { return bytes_.empty(); }

 private:
  void get_bytes(void* to, std::size_t size) {
    if (bytes_.size() < size) fail();
    if (size > 0) std::memcpy(to, bytes_.data(), size);
    bytes_.remove_prefix(size);
  }
  [[noreturn]] void fail() const { throw Error(end_message_); }

  std::string_view bytes_;
  std::string end_message_;
};

}  // namespace owsim
