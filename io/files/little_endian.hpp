#pragma once
// Little-endian byte order for the sensor's word files (SENSOR-SPEC §8), independent of the host.
#include <cstddef>
#include <cstdint>

namespace owsim {

template <typename UInt>
void store_little_endian(UInt value, unsigned char* bytes) {
  for (std::size_t i = 0; i < sizeof(UInt); ++i)
    bytes[i] = static_cast<unsigned char>(value >> (8 * i));
}

template <typename UInt>
[[nodiscard]] UInt load_little_endian(const unsigned char* bytes) {
  UInt value = 0;
  for (std::size_t i = 0; i < sizeof(UInt); ++i)
    value |= static_cast<UInt>(static_cast<UInt>(bytes[i]) << (8 * i));
  return value;
}

}  // namespace owsim
