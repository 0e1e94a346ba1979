// Protects the MilOWS 64-bit word layout (SENSOR-SPEC §8, table 4): every field at its limits,
// a word computed by hand, its little-endian bytes on disk, and bit-exact round trips.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

#include "geometry/error.hpp"
#include "io/recording/milows_word.hpp"
#include "io/recording/word_file.hpp"

namespace owsim {
namespace {

TEST(MilowsWord, HandComputedWord) {
  MilowsWord word;
  word.time_tag = 0x1234;
  word.encoder = -21101;  // β = 0 (SENSOR-SPEC §3): 65536 − 21101 = 44435 = 0xAD93
  word.frame_gate = true;
  word.line_gate = true;
  word.counter2 = 2066;  // 0x812
  word.counter1 = 100;   // 0x064
  // 0x1234 | 0xAD93 | FG LG → 0xC000'0000 | 0x812 << 16 | 0x064
  constexpr std::uint64_t expected = 0x1234'AD93'C812'0064ull;
  EXPECT_EQ(pack(word), expected);
  EXPECT_EQ(unpack_milows(expected), word);
}

TEST(MilowsWord, HandComputedWordIsLittleEndianOnDisk) {
  const auto path = std::filesystem::temp_directory_path() / "owsim_test_milows_word.d64";
  MilowsWordWriter writer(path, {.sync_on_commit = false});
  writer.write(0x1234'AD93'C812'0064ull);
  writer.commit();
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), {}};
  const std::vector<unsigned char> expected = {0x64, 0x00, 0x12, 0xC8, 0x93, 0xAD, 0x34, 0x12};
  EXPECT_EQ(bytes, expected);
  std::filesystem::remove(path);
}

TEST(MilowsWord, EachFieldAtItsLimitsSitsInItsBits) {
  const auto only = [](auto set) {
    MilowsWord word;
    set(word);
    return pack(word);
  };
  EXPECT_EQ(pack(MilowsWord{}), 0u);
  EXPECT_EQ(only([](MilowsWord& w) { w.time_tag = 0xFFFF; }), 0xFFFF'0000'0000'0000ull);
  EXPECT_EQ(only([](MilowsWord& w) { w.encoder = std::numeric_limits<EncoderCount>::min(); }),
            0x0000'8000'0000'0000ull);
  EXPECT_EQ(only([](MilowsWord& w) { w.encoder = std::numeric_limits<EncoderCount>::max(); }),
            0x0000'7FFF'0000'0000ull);
  EXPECT_EQ(only([](MilowsWord& w) { w.encoder = -1; }), 0x0000'FFFF'0000'0000ull);
  EXPECT_EQ(only([](MilowsWord& w) { w.frame_gate = true; }), 1ull << 31);
  EXPECT_EQ(only([](MilowsWord& w) { w.line_gate = true; }), 1ull << 30);
  EXPECT_EQ(only([](MilowsWord& w) { w.crosstalk = true; }), 1ull << 29);
  EXPECT_EQ(only([](MilowsWord& w) { w.reserved28 = true; }), 1ull << 28);
  EXPECT_EQ(only([](MilowsWord& w) { w.counter2 = 4095; }), 0x0FFFull << 16);
  EXPECT_EQ(only([](MilowsWord& w) { w.lut = 3; }), 3ull << 14);
  EXPECT_EQ(only([](MilowsWord& w) { w.trigger = 3; }), 3ull << 12);
  EXPECT_EQ(only([](MilowsWord& w) { w.counter1 = 4095; }), 0x0FFFull);

  MilowsWord limits;
  for (const EncoderCount encoder : {EncoderCount{-32768}, EncoderCount{0}, EncoderCount{32767}}) {
    for (const std::uint16_t counter :
         {std::uint16_t{0}, std::uint16_t{2066}, std::uint16_t{4095}}) {
      limits.encoder = encoder;
      limits.counter1 = counter;
      limits.counter2 = static_cast<std::uint16_t>(4095 - counter);
      limits.time_tag = static_cast<std::uint16_t>(counter * 16);
      EXPECT_EQ(unpack_milows(pack(limits)), limits);
    }
  }
}

TEST(MilowsWord, EveryBitPatternRoundTrips) {
  std::mt19937_64 random(20240611);
  for (int i = 0; i < 100'000; ++i) {
    const std::uint64_t bits = random();
    ASSERT_EQ(pack(unpack_milows(bits)), bits) << std::hex << bits;
  }
  constexpr std::uint64_t all_ones = ~0ull;
  EXPECT_EQ(pack(unpack_milows(all_ones)), all_ones);
  const MilowsWord ones = unpack_milows(all_ones);
  EXPECT_EQ(ones.time_tag, 0xFFFF);
  EXPECT_EQ(ones.encoder, -1);
  EXPECT_TRUE(ones.frame_gate && ones.line_gate && ones.crosstalk && ones.reserved28);
  EXPECT_EQ(ones.counter2, 4095);
  EXPECT_EQ(ones.lut, 3);
  EXPECT_EQ(ones.trigger, 3);
  EXPECT_EQ(ones.counter1, 4095);
}

TEST(MilowsWord, PackRefusesFieldsWiderThanTheirBits) {
  MilowsWord word;
  word.counter1 = 4096;
  EXPECT_THROW((void)pack(word), Error);
  word = {};
  word.counter2 = 4096;
  EXPECT_THROW((void)pack(word), Error);
  word = {};
  word.lut = 4;
  EXPECT_THROW((void)pack(word), Error);
  word = {};
  word.trigger = 4;
  EXPECT_THROW((void)pack(word), Error);
  word = {};
  word.counter1 = 4095;
  EXPECT_NO_THROW((void)pack(word));
  word.counter1 = 4096;
  try {
    (void)pack(word);
    FAIL() << "counter 1 = 4096 packed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("counter 1 = 4096"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace owsim
