// Protects the streaming word files (SENSOR-SPEC §8): what is written reads back word for word in
// any chunking, bytes on disk are little-endian, a cut inside a word is reported, not hidden.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "io/recording/word_file.hpp"
#include "test_recording_check_fixture.hpp"

namespace owsim {
namespace {

class WordFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fixture::fresh_directory(std::string("word_file_") +
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::vector<unsigned char> bytes_of(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }

  template <typename Word>
  static std::vector<Word> read_all(WordFileReader<Word>& reader, std::size_t chunk_words) {
    std::vector<Word> all, chunk(chunk_words);
    while (const std::size_t n = reader.read(chunk))
      all.insert(all.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n));
    return all;
  }

  std::filesystem::path dir_;
};

TEST_F(WordFile, ThreeMilowsFramesReadBackWordForWord) {
  const auto words = fixture::milows_words(3);
  const auto path = dir_ / "flight.d64";
  MilowsWordWriter writer(path);
  for (int frame = 0; frame < 3; ++frame) {  // a whole frame at a time
    writer.write(std::span(words).subspan(
        static_cast<std::size_t>(frame) * fixture::kPulsesPerFrame, fixture::kPulsesPerFrame));
  }
  EXPECT_EQ(writer.words_written(), words.size());
  writer.commit();
  EXPECT_EQ(std::filesystem::file_size(path), words.size() * 8);

  MilowsWordReader reader(path);
  EXPECT_EQ(reader.words_total(), words.size());
  EXPECT_EQ(reader.trailing_bytes(), 0u);
  EXPECT_EQ(read_all(reader, 1 << 16), words);
  EXPECT_EQ(reader.words_read(), words.size());
  std::vector<std::uint64_t> more(4);
  EXPECT_EQ(reader.read(more), 0u);
}

TEST_F(WordFile, HellasWordsReadBackWordForWord) {
  const auto words = fixture::hellas_words(3);
  const auto path = dir_ / "flight.hellas";
  HellasWordWriter writer(path, {}, 1000);  // a buffer far smaller than a frame
  writer.write(words);
  writer.commit();
  HellasWordReader reader(path);
  EXPECT_EQ(reader.words_total(), words.size());
  EXPECT_EQ(read_all(reader, 4096), words);
}

TEST_F(WordFile, ChunksSmallerThanAFrameGiveTheSameWords) {
  const auto words = fixture::milows_words(2);
  const auto path = dir_ / "flight.d64";
  fixture::write_words<std::uint64_t>(path, words);
  for (const std::size_t buffer_bytes : {std::size_t{8}, std::size_t{1000}, std::size_t{1} << 20}) {
    for (const std::size_t chunk_words : {std::size_t{1}, std::size_t{777}, std::size_t{20'351}}) {
      if (chunk_words == 1 && buffer_bytes != 1000) continue;  // one word at a time: once is enough
      MilowsWordReader reader(path, buffer_bytes);
      EXPECT_EQ(read_all(reader, chunk_words), words) << buffer_bytes << " " << chunk_words;
    }
  }
}

TEST_F(WordFile, BytesOnDiskAreLittleEndian) {
  const std::vector<std::uint64_t> milows = {0x0102'0304'0506'0708ull, 0xF0E1'D2C3'B4A5'9687ull};
  const std::vector<std::uint32_t> hellas = {0x0A0B'0C0Du, 0x8000'00FFu};
  MilowsWordWriter milows_writer(dir_ / "a.d64");
  milows_writer.write(milows);
  milows_writer.commit();
  HellasWordWriter hellas_writer(dir_ / "a.hellas");
  hellas_writer.write(hellas);
  hellas_writer.commit();

  const auto milows_bytes = bytes_of(dir_ / "a.d64");
  ASSERT_EQ(milows_bytes.size(), 16u);
  for (std::size_t w = 0; w < milows.size(); ++w) {
    for (std::size_t b = 0; b < 8; ++b) {
      EXPECT_EQ(milows_bytes[8 * w + b], (milows[w] >> (8 * b)) & 0xFF)
          << "word " << w << " byte " << b;
    }
  }
  EXPECT_EQ(milows_bytes[0], 0x08);
  EXPECT_EQ(milows_bytes[7], 0x01);
  const std::vector<unsigned char> hellas_expected = {0x0D, 0x0C, 0x0B, 0x0A,
                                                      0xFF, 0x00, 0x00, 0x80};
  EXPECT_EQ(bytes_of(dir_ / "a.hellas"), hellas_expected);
}

TEST_F(WordFile, TrailingBytesAreReportedNotReturned) {
  const auto words = fixture::milows_words(1);
  const auto path = dir_ / "cut.d64";
  fixture::write_words<std::uint64_t>(path, words);
  { std::ofstream(path, std::ios::binary | std::ios::app) << "xyz"; }
  MilowsWordReader reader(path);
  EXPECT_EQ(reader.file_bytes(), words.size() * 8 + 3);
  EXPECT_EQ(reader.words_total(), words.size());
  EXPECT_EQ(reader.trailing_bytes(), 3u);
  EXPECT_EQ(read_all(reader, 1000), words);

  // The same bytes read as 32-bit words: 3 trailing bytes too.
  HellasWordReader as_hellas(path);
  EXPECT_EQ(as_hellas.words_total(), words.size() * 2);
  EXPECT_EQ(as_hellas.trailing_bytes(), 3u);
}

TEST_F(WordFile, UncommittedWriterLeavesNothing) {
  const auto path = dir_ / "never.d64";
  {
    const auto words = fixture::milows_words(1);
    MilowsWordWriter writer(path);
    writer.write(words);
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(path)));
}

TEST_F(WordFile, ReaderErrorsNameThePath) {
  const auto missing = dir_ / "missing.d64";
  try {
    MilowsWordReader reader(missing);
    FAIL() << "opened a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  try {
    HellasWordReader reader(dir_);
    FAIL() << "opened a directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir_.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace owsim
