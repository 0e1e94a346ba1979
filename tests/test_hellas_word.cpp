// Protects the HELLAS 32-bit word layout (SENSOR-SPEC §8, table 3): every field at its limits,
// a word computed by hand, its little-endian bytes on disk, and bit-exact round trips.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

#include "geometry/error.hpp"
#include "io/recording/hellas_word.hpp"
#include "io/recording/word_file.hpp"

namespace owsim {
namespace {

TEST(HellasWord, HandComputedWord) {
  HellasWord word;
  word.select = false;
  word.zt = true;
  word.time_tag = 0x2ABC;
  word.ain = true;
  word.ni = false;
  word.mov_dir = true;
  word.bt = true;
  word.counter = 0x7FF;
  // ZT 0x4000'0000 | 0x2ABC << 16 | Ain 0x8000 | MovDir 0x2000 | BT 0x1000 | 0x7FF
  constexpr std::uint32_t expected = 0x6ABC'B7FFu;
  EXPECT_EQ(pack(word), expected);
  EXPECT_EQ(unpack_hellas(expected), word);
}

TEST(HellasWord, HandComputedWordIsLittleEndianOnDisk) {
  const auto path = std::filesystem::temp_directory_path() / "owsim_test_hellas_word.hellas";
  HellasWordWriter writer(path, {.sync_on_commit = false});
  writer.write(0x6ABC'B7FFu);
  writer.commit();
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), {}};
  const std::vector<unsigned char> expected = {0xFF, 0xB7, 0xBC, 0x6A};
  EXPECT_EQ(bytes, expected);
  std::filesystem::remove(path);
}

TEST(HellasWord, DefaultsAreTheInactiveGates) {
  // ZT and BT are active low: a default word is a plain pulse, neither line nor frame end.
  EXPECT_EQ(pack(HellasWord{}), (1u << 30) | (1u << 12));
}

TEST(HellasWord, EachFieldAtItsLimitsSitsInItsBits) {
  HellasWord none;
  none.zt = false;
  none.bt = false;
  EXPECT_EQ(pack(none), 0u);
  const auto only = [&](auto set) {
    HellasWord word = none;
    set(word);
    return pack(word);
  };
  EXPECT_EQ(only([](HellasWord& w) { w.select = true; }), 1u << 31);
  EXPECT_EQ(only([](HellasWord& w) { w.zt = true; }), 1u << 30);
  EXPECT_EQ(only([](HellasWord& w) { w.time_tag = 0x3FFF; }), 0x3FFFu << 16);
  EXPECT_EQ(only([](HellasWord& w) { w.ain = true; }), 1u << 15);
  EXPECT_EQ(only([](HellasWord& w) { w.ni = true; }), 1u << 14);
  EXPECT_EQ(only([](HellasWord& w) { w.mov_dir = true; }), 1u << 13);
  EXPECT_EQ(only([](HellasWord& w) { w.bt = true; }), 1u << 12);
  EXPECT_EQ(only([](HellasWord& w) { w.counter = 4095; }), 0xFFFu);
  for (const std::uint16_t tag : {std::uint16_t{0}, std::uint16_t{1}, std::uint16_t{16383}}) {
    for (const std::uint16_t counter :
         {std::uint16_t{0}, std::uint16_t{2066}, std::uint16_t{4095}}) {
      HellasWord word;
      word.time_tag = tag;
      word.counter = counter;
      word.select = counter == 4095;
      EXPECT_EQ(unpack_hellas(pack(word)), word);
    }
  }
}

TEST(HellasWord, EveryBitPatternRoundTrips) {
  std::mt19937 random(20240611);
  for (int i = 0; i < 100'000; ++i) {
    const std::uint32_t bits = random();
    ASSERT_EQ(pack(unpack_hellas(bits)), bits) << std::hex << bits;
  }
  const HellasWord ones = unpack_hellas(0xFFFF'FFFFu);
  EXPECT_EQ(pack(ones), 0xFFFF'FFFFu);
  EXPECT_TRUE(ones.select && ones.zt && ones.ain && ones.ni && ones.mov_dir && ones.bt);
  EXPECT_EQ(ones.time_tag, 0x3FFF);
  EXPECT_EQ(ones.counter, 4095);
}

TEST(HellasWord, PackRefusesFieldsWiderThanTheirBits) {
  HellasWord word;
  word.counter = 4096;
  EXPECT_THROW((void)pack(word), Error);
  word = {};
  word.time_tag = 16384;
  EXPECT_THROW((void)pack(word), Error);
}

}  // namespace
}  // namespace owsim
