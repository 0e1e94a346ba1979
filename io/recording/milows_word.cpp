#include "io/recording/milows_word.hpp"

namespace owsim {
namespace {

bool test(std::uint64_t bits, int bit) { return ((bits >> bit) & 1u) != 0; }

}  // namespace

MilowsWord unpack_milows(std::uint64_t bits) {
  using namespace milows_bits;
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
