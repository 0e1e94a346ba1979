#include "io/mcap/cdr_writer.hpp"

#include <bit>
#include <limits>
#include <string>

#include "geometry/error.hpp"

namespace owsim {

void CdrWriter::clear() {
  bytes_.assign({0x00, 0x01, 0x00, 0x00});  // CDR_LE, options 0
}

void CdrWriter::align(std::size_t size) {
  const std::size_t misalignment = (bytes_.size() - kCdrHeaderBytes) % size;
  if (misalignment != 0) bytes_.insert(bytes_.end(), size - misalignment, 0);
}

void CdrWriter::f32(float value) { put(std::bit_cast<std::uint32_t>(value)); }

void CdrWriter::f64(double value) { put(std::bit_cast<std::uint64_t>(value)); }

void CdrWriter::string(std::string_view text) {
  if (text.find('\0') != std::string_view::npos) {
    throw Error("CDR string holds a NUL byte: \"" + std::string(text.substr(0, text.find('\0'))) +
                "\\0…\"");
  }
  if (text.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw Error("CDR string of " + std::to_string(text.size()) + " bytes is too long");
  }
  u32(static_cast<std::uint32_t>(text.size() + 1));
  bytes_.insert(bytes_.end(), text.begin(), text.end());
  bytes_.push_back(0);
}

void CdrWriter::sequence_size(std::size_t count) {
  if (count > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("CDR sequence of " + std::to_string(count) + " elements is too long");
  }
  u32(static_cast<std::uint32_t>(count));
}

void CdrWriter::byte_sequence(std::span<const unsigned char> bytes) {
  sequence_size(bytes.size());
  bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
}

}  // namespace owsim
