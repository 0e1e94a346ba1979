#pragma once
// A record of numbers and byte strings in a fixed little-endian layout, whatever the host: the
// binary run checkpoint (io/run/run_checkpoint.hpp). Integers are stored at their own width,
// doubles as their IEEE-754 bits (exact), byte strings as a u64 length and the bytes.
#include <bit>
#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>

#include "geometry/error.hpp"
#include "io/files/little_endian.hpp"

namespace owsim {

class BinaryRecordWriter {
 public:
  template <std::integral Int>
  void put(Int value) {
    using UInt = std::make_unsigned_t<Int>;
    unsigned char bytes[sizeof(UInt)];
    store_little_endian(static_cast<UInt>(value), bytes);
    bytes_.append(reinterpret_cast<const char*>(bytes), sizeof bytes);
  }
  void put(double value) { put(std::bit_cast<std::uint64_t>(value)); }
  void put(bool value) = delete;  // say the width: put(std::uint8_t{…})
  void put_bytes(std::string_view bytes) {
    put(static_cast<std::uint64_t>(bytes.size()));
    bytes_ += bytes;
  }
  [[nodiscard]] const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what BinaryRecordWriter wrote, in the same order. Throws owsim::Error "the record ends
// early" when a value runs past the end.
class BinaryRecordReader {
 public:
  explicit BinaryRecordReader(std::string_view bytes) : bytes_(bytes) {}
  template <std::integral Int>
  [[nodiscard]] Int get() {
    using UInt = std::make_unsigned_t<Int>;
    const auto* bytes = reinterpret_cast<const unsigned char*>(take(sizeof(UInt)).data());
    return static_cast<Int>(load_little_endian<UInt>(bytes));
  }
  [[nodiscard]] double get_double() { return std::bit_cast<double>(get<std::uint64_t>()); }
  [[nodiscard]] std::string_view get_bytes() {
    const auto size = get<std::uint64_t>();
    if (size > bytes_.size()) throw Error("the record ends early");
    return take(static_cast<std::size_t>(size));
  }
  [[nodiscard]] std::size_t left() const { return bytes_.size(); }

 private:
  std::string_view take(std::size_t size) {
    if (size > bytes_.size()) throw Error("the record ends early");
    const std::string_view part = bytes_.substr(0, size);
    bytes_.remove_prefix(size);
    return part;
  }
  std::string_view bytes_;
};

}  // namespace owsim
