#pragma once
// Little-endian CDR as ROS 2 serializes its messages (XCDR1 PLAIN_CDR, the OMG DDS-XTypes
// encapsulation CDR_LE): the 4-byte encapsulation header 00 01 00 00, then each primitive aligned
// to its own size (1, 2, 4 or 8 bytes), counted from the byte after the header, padding bytes 0;
// a string is a uint32 length counting its terminating NUL, the bytes and the NUL; a sequence is a
// uint32 element count and the elements. Bytes only grow: clear() starts the next message in the
// same buffer, so a writer reused from message to message allocates only while it grows.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace owsim {

inline constexpr std::size_t kCdrHeaderBytes = 4;

class CdrWriter {
 public:
  CdrWriter() { clear(); }
  // Back to the encapsulation header alone.
  void clear();

  void u8(std::uint8_t value) { bytes_.push_back(value); }
  void i8(std::int8_t value) { u8(static_cast<std::uint8_t>(value)); }
  void boolean(bool value) { u8(value ? 1 : 0); }
  void u16(std::uint16_t value) { put(value); }
  void i16(std::int16_t value) { put(static_cast<std::uint16_t>(value)); }
  void u32(std::uint32_t value) { put(value); }
  void i32(std::int32_t value) { put(static_cast<std::uint32_t>(value)); }
  void u64(std::uint64_t value) { put(value); }
  void i64(std::int64_t value) { put(static_cast<std::uint64_t>(value)); }
  void f32(float value);
  void f64(double value);
  // Throws owsim::Error if the text holds a NUL or is longer than a uint32 length can say.
  void string(std::string_view text);
  // The count before a sequence's elements. Throws owsim::Error past the uint32 range.
  void sequence_size(std::size_t count);
  // A uint8[] sequence: its count and its bytes.
  void byte_sequence(std::span<const unsigned char> bytes);

  [[nodiscard]] std::span<const unsigned char> bytes() const { return bytes_; }
  [[nodiscard]] std::size_t size() const { return bytes_.size(); }
  [[nodiscard]] std::size_t capacity() const { return bytes_.capacity(); }

 private:
  template <typename UInt>
  void put(UInt value) {
    align(sizeof(UInt));
    for (std::size_t i = 0; i < sizeof(UInt); ++i)
      bytes_.push_back(static_cast<unsigned char>(value >> (8 * i)));
  }
  void align(std::size_t size);

  std::vector<unsigned char> bytes_;
};

}  // namespace owsim
