#include "io/recording/hellas_word.hpp"

#include "io/recording/word_field.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
// Where each field sits in the word (as milows_bits does for MilOWS).
namespace hellas_bits {

constexpr int kSelectBit = 31;
constexpr int kZtBit = 30;
constexpr int kTimeTagShift = 16;
constexpr int kAinBit = 15;
constexpr int kNiBit = 14;
constexpr int kMovDirBit = 13;
constexpr int kBtBit = 12;
constexpr std::uint32_t kCounterMask = 0xFFF;

std::uint32_t flag(bool value, int bit) { return static_cast<std::uint32_t>(value) << bit; }
bool test(std::uint32_t bits, int bit) { return ((bits >> bit) & 1u) != 0; }

}  // namespace hellas_bits

std::uint32_t pack(const HellasWord& word) {
  using namespace hellas_bits;
  require_field_width("HELLAS", "time tag", word.time_tag, kHellasTimeTagMax);
  require_field_width("HELLAS", "counter", word.counter, kCounterMax);
  return flag(word.select, kSelectBit) | flag(word.zt, kZtBit) |
         static_cast<std::uint32_t>(word.time_tag) << kTimeTagShift | flag(word.ain, kAinBit) |
         flag(word.ni, kNiBit) | flag(word.mov_dir, kMovDirBit) | flag(word.bt, kBtBit) |
         word.counter;
}

HellasWord unpack_hellas(std::uint32_t bits) {
  using namespace hellas_bits;
  HellasWord word;
  word.select = test(bits, kSelectBit);
  word.zt = test(bits, kZtBit);
  word.time_tag = static_cast<std::uint16_t>((bits >> kTimeTagShift) & kHellasTimeTagMax);
  word.ain = test(bits, kAinBit);
  word.ni = test(bits, kNiBit);
  word.mov_dir = test(bits, kMovDirBit);
  word.bt = test(bits, kBtBit);
  word.counter = static_cast<std::uint16_t>(bits & kCounterMask);
  return word;
}

}  // namespace owsim
