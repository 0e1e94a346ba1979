#include "io/recording/milows_word.hpp"

#include "io/recording/word_field.hpp"
#include "sensor/range_counter.hpp"

namespace owsim {
namespace {

constexpr int kTimeTagShift = 48;
constexpr int kEncoderShift = 32;
constexpr int kFrameGateBit = 31;
constexpr int kLineGateBit = 30;
constexpr int kCrosstalkBit = 29;
constexpr int kReservedBit = 28;
constexpr int kCounter2Shift = 16;
constexpr int kLutShift = 14;
constexpr int kTriggerShift = 12;
constexpr std::uint64_t kCounterMask = 0xFFF;
constexpr std::uint64_t kTwoBitMask = 0x3;

std::uint64_t flag(bool value, int bit) { return static_cast<std::uint64_t>(value) << bit; }
bool test(std::uint64_t bits, int bit) { return ((bits >> bit) & 1u) != 0; }

}  // namespace

std::uint64_t pack(const MilowsWord& word) {
  require_field_width("MilOWS", "counter 1", word.counter1, kCounterMax);
  require_field_width("MilOWS", "counter 2", word.counter2, kCounterMax);
  require_field_width("MilOWS", "LUT", word.lut, kMilowsTwoBitMax);
  require_field_width("MilOWS", "trigger", word.trigger, kMilowsTwoBitMax);
  const auto encoder_bits = static_cast<std::uint16_t>(word.encoder);
  return static_cast<std::uint64_t>(word.time_tag) << kTimeTagShift |
         static_cast<std::uint64_t>(encoder_bits) << kEncoderShift |
         flag(word.frame_gate, kFrameGateBit) | flag(word.line_gate, kLineGateBit) |
         flag(word.crosstalk, kCrosstalkBit) | flag(word.reserved28, kReservedBit) |
         static_cast<std::uint64_t>(word.counter2) << kCounter2Shift |
         static_cast<std::uint64_t>(word.lut) << kLutShift |
         static_cast<std::uint64_t>(word.trigger) << kTriggerShift | word.counter1;
}

MilowsWord unpack_milows(std::uint64_t bits) {
  MilowsWord word;
  word.time_tag = static_cast<std::uint16_t>(bits >> kTimeTagShift);
  word.encoder = static_cast<EncoderCount>(static_cast<std::uint16_t>(bits >> kEncoderShift));
  word.frame_gate = test(bits, kFrameGateBit);
  word.line_gate = test(bits, kLineGateBit);
  word.crosstalk = test(bits, kCrosstalkBit);
  word.reserved28 = test(bits, kReservedBit);
  word.counter2 = static_cast<std::uint16_t>((bits >> kCounter2Shift) & kCounterMask);
  word.lut = static_cast<std::uint8_t>((bits >> kLutShift) & kTwoBitMask);
  word.trigger = static_cast<std::uint8_t>((bits >> kTriggerShift) & kTwoBitMask);
  word.counter1 = static_cast<std::uint16_t>(bits & kCounterMask);
  return word;
}

}  // namespace owsim
