// io/mcap: the MCAP writer's records byte for byte, CRC-32, CDR alignment, chunking and its
// summary, bounded buffers, the ROS 2 schemas and QoS metadata. The reference readers' check of a
// whole file is tests/mcap/read_mcap.mjs (ctest mcap_reference_reader).
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/error.hpp"
#include "io/mcap/cdr_writer.hpp"
#include "io/mcap/lidar_point_cloud.hpp"
#include "io/mcap/mcap_records.hpp"
#include "io/mcap/mcap_writer.hpp"
#include "io/mcap/ros2_messages.hpp"
#include "io/mcap/ros2_msg_definitions.hpp"
#include "io/mcap/ros2_qos.hpp"

namespace owsim {
namespace {

using Bytes = std::vector<unsigned char>;

class MemorySink final : public McapSink {
 public:
  void write(std::span<const unsigned char> bytes) override {
    data.insert(data.end(), bytes.begin(), bytes.end());
  }
  void finish() override { finished = true; }
  Bytes data;
  bool finished = false;
};

// The expected bytes, spelled out field by field (independent of io/mcap/mcap_records.cpp).
struct Expect {
  Bytes bytes;
  Expect& u8(std::uint8_t v) {
    bytes.push_back(v);
    return *this;
  }
  Expect& le(std::uint64_t v, int width) {
    for (int i = 0; i < width; ++i) bytes.push_back(static_cast<unsigned char>(v >> (8 * i)));
    return *this;
  }
  Expect& u16(std::uint64_t v) { return le(v, 2); }
  Expect& u32(std::uint64_t v) { return le(v, 4); }
  Expect& u64(std::uint64_t v) { return le(v, 8); }
  Expect& raw(std::string_view s) {
    bytes.insert(bytes.end(), s.begin(), s.end());
    return *this;
  }
  Expect& str(std::string_view s) { return u32(s.size()).raw(s); }
};

std::uint64_t load(const Bytes& bytes, std::size_t at, int width) {
  std::uint64_t v = 0;
  for (int i = 0; i < width; ++i) v |= std::uint64_t{bytes.at(at + i)} << (8 * i);
  return v;
}

std::uint32_t zlib_crc(const Bytes& bytes, std::size_t begin, std::size_t end) {
  return static_cast<std::uint32_t>(
      ::crc32(0, bytes.data() + begin, static_cast<uInt>(end - begin)));
}

TEST(McapCrc, CheckValueOfTheStandardString) {
  const std::string_view text = "123456789";
  const Bytes bytes(text.begin(), text.end());
  EXPECT_EQ(mcap::crc32(0, bytes), 0xCBF43926u);
  // Continued over two pieces, the same.
  EXPECT_EQ(mcap::crc32(mcap::crc32(0, std::span(bytes).first(4)), std::span(bytes).subspan(4)),
            0xCBF43926u);
}

TEST(McapWriter, TinyFileByteForByte) {
  MemorySink sink;
  McapWriterOptions options;
  options.library = "lib";
  options.compression = McapCompression::none;
  McapWriter writer(sink, "tiny.mcap", options);
  const auto schema = writer.add_schema("pkg/msg/T", "ros2msg", "uint8 a\n");
  const auto channel = writer.add_channel(schema, "/t", "cdr", {{"k", "v"}});
  const Bytes payload{0x00, 0x01, 0x00, 0x00, 0x2A};
  writer.write_message(channel, 7, 9, payload);
  writer.finish();
  ASSERT_TRUE(sink.finished);
  EXPECT_EQ(schema, 1);
  EXPECT_EQ(channel, 1);

  Expect records;  // the chunk's content
  records.u8(0x03)
      .u64(2 + 4 + 9 + 4 + 7 + 4 + 8)
      .u16(1)
      .str("pkg/msg/T")
      .str("ros2msg")
      .str("uint8 a\n");
  const std::size_t channel_at = records.bytes.size();
  records.u8(0x04)
      .u64(2 + 2 + 4 + 2 + 4 + 3 + 4 + 10)
      .u16(1)
      .u16(1)
      .str("/t")
      .str("cdr")
      .u32(10)
      .str("k")
      .str("v");
  const std::size_t message_at = records.bytes.size();
  records.u8(0x05)
      .u64(2 + 4 + 8 + 8 + 5)
      .u16(1)
      .u32(0)
      .u64(7)
      .u64(9)
      .raw(std::string_view("\x00\x01\x00\x00\x2A", 5));
  const std::size_t records_size = records.bytes.size();

  Expect file;
  file.raw(std::string_view("\x89MCAP0\r\n", 8));
  file.u8(0x01).u64(4 + 4 + 4 + 3).str("ros2").str("lib");
  const std::size_t chunk_at = file.bytes.size();
  file.u8(0x06)
      .u64(8 + 8 + 8 + 4 + 4 + 0 + 8 + records_size)
      .u64(7)
      .u64(7)
      .u64(records_size)
      .u32(zlib_crc(records.bytes, 0, records_size))
      .str("")
      .u64(records_size);
  file.bytes.insert(file.bytes.end(), records.bytes.begin(), records.bytes.end());
  const std::size_t chunk_length = file.bytes.size() - chunk_at;
  const std::size_t index_at = file.bytes.size();
  file.u8(0x07).u64(2 + 4 + 16).u16(1).u32(16).u64(7).u64(message_at);
  const std::size_t index_length = file.bytes.size() - index_at;
  const std::uint32_t data_crc = zlib_crc(file.bytes, 0, file.bytes.size());  // before Data End
  file.u8(0x0F).u64(4).u32(data_crc);
  const std::size_t summary_at = file.bytes.size();
  file.bytes.insert(file.bytes.end(), records.bytes.begin(), records.bytes.begin() + message_at);
  const std::size_t statistics_at = file.bytes.size();
  file.u8(0x0B)
      .u64(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8 + 4 + 10)
      .u64(1)
      .u16(1)
      .u32(1)
      .u32(0)
      .u32(0)
      .u32(1)
      .u64(7)
      .u64(7)
      .u32(10)
      .u16(1)
      .u64(1);
  const std::size_t chunk_index_at = file.bytes.size();
  file.u8(0x08)
      .u64(8 + 8 + 8 + 8 + 4 + 10 + 8 + 4 + 8 + 8)
      .u64(7)
      .u64(7)
      .u64(chunk_at)
      .u64(chunk_length)
      .u32(10)
      .u16(1)
      .u64(index_at)
      .u64(index_length)
      .str("")
      .u64(records_size)
      .u64(records_size);
  const std::size_t offsets_at = file.bytes.size();
  file.u8(0x0E).u64(17).u8(0x03).u64(summary_at).u64(channel_at);
  file.u8(0x0E).u64(17).u8(0x04).u64(summary_at + channel_at).u64(message_at - channel_at);
  file.u8(0x0E).u64(17).u8(0x0B).u64(statistics_at).u64(chunk_index_at - statistics_at);
  file.u8(0x0E).u64(17).u8(0x08).u64(chunk_index_at).u64(offsets_at - chunk_index_at);
  file.u8(0x02).u64(20).u64(summary_at).u64(offsets_at);
  const std::uint32_t summary_crc = zlib_crc(file.bytes, summary_at, file.bytes.size());
  file.u32(summary_crc);
  file.raw(std::string_view("\x89MCAP0\r\n", 8));

  ASSERT_EQ(sink.data.size(), file.bytes.size());
  for (std::size_t i = 0; i < file.bytes.size(); ++i) {
    ASSERT_EQ(int{sink.data[i]}, int{file.bytes[i]}) << "byte " << i;
  }
  EXPECT_EQ(writer.bytes_written(), file.bytes.size());
}

TEST(McapWriter, LibraryIsOwsimAndItsVersionByDefault) {
  MemorySink sink;
  McapWriter writer(sink, "x.mcap");
  writer.finish();
  const std::string head(sink.data.begin() + 8 + 9, sink.data.begin() + 8 + 9 + 4 + 4 + 4 + 6);
  EXPECT_EQ(head, std::string("\x04\0\0\0ros2\x0b\0\0\0owsim ", 18).substr(0, head.size()));
}

// Walks the records from the start: opcodes in order, and the chunks' positions.
struct Walk {
  std::vector<int> opcodes;
  std::vector<std::size_t> offsets;
};
Walk walk(const Bytes& file) {
  Walk walk;
  std::size_t at = 8;
  while (at + 9 <= file.size() - 8) {
    walk.opcodes.push_back(file[at]);
    walk.offsets.push_back(at);
    at += 9 + load(file, at + 1, 8);
  }
  EXPECT_EQ(at, file.size() - 8);
  return walk;
}

TEST(McapWriter, SeveralChunksHaveOneChunkIndexEachAndAFooterThatPointsAtTheSummary) {
  MemorySink sink;
  McapWriterOptions options;
  options.chunk_size = 1000;
  McapWriter writer(sink, "chunks.mcap", options);
  const auto schema = writer.add_schema("pkg/msg/T", "ros2msg", "uint8[] a\n");
  const auto a = writer.add_channel(schema, "/a", "cdr");
  const auto b = writer.add_channel(schema, "/b", "cdr");
  const Bytes payload(300, 0x55);
  for (std::uint64_t i = 0; i < 19; ++i) writer.write_message(i % 3 == 0 ? b : a, 100 + i, payload);
  writer.finish();
  const Bytes& file = sink.data;
  const Walk records = walk(file);
  const auto count = [&](int opcode) {
    return std::count(records.opcodes.begin(), records.opcodes.end(), opcode);
  };
  // 331-byte message records close a 1000-byte chunk at the 4th message, the first chunk (which
  // holds the schema and the channels too) at the 3rd: 5 chunks of 3 + 4·4 messages.
  EXPECT_EQ(writer.chunks_written(), 5u);
  EXPECT_EQ(count(0x06), 5);
  EXPECT_EQ(count(0x08), 5);
  EXPECT_EQ(count(0x07), 10);  // every chunk has messages on both channels
  EXPECT_EQ(count(0x0F), 1);
  EXPECT_EQ(records.opcodes.front(), 0x01);
  EXPECT_EQ(records.opcodes.back(), 0x02);
  // Each chunk is followed by its message indexes; the chunk indexes point at the chunks.
  std::vector<std::size_t> chunk_offsets, indexed_offsets;
  for (std::size_t i = 0; i < records.opcodes.size(); ++i) {
    if (records.opcodes[i] == 0x06) {
      chunk_offsets.push_back(records.offsets[i]);
      EXPECT_EQ(records.opcodes[i + 1], 0x07);
      EXPECT_EQ(records.opcodes[i + 2], 0x07);
    }
    if (records.opcodes[i] == 0x08)
      indexed_offsets.push_back(load(file, records.offsets[i] + 25, 8));
  }
  EXPECT_EQ(indexed_offsets, chunk_offsets);
  // Footer: summary_start at the first summary record (a Schema after Data End), the summary
  // offsets after the chunk indexes, and the CRCs of both sections.
  const std::size_t footer = records.offsets.back();
  const std::size_t summary_start = load(file, footer + 9, 8);
  const std::size_t summary_offset_start = load(file, footer + 17, 8);
  const auto data_end = std::find(records.opcodes.begin(), records.opcodes.end(), 0x0F);
  const std::size_t data_end_at = records.offsets[data_end - records.opcodes.begin()];
  EXPECT_EQ(summary_start, data_end_at + 9 + 4);
  EXPECT_EQ(file[summary_start], 0x03);
  EXPECT_EQ(file[summary_offset_start], 0x0E);
  EXPECT_EQ(load(file, data_end_at + 9, 4), zlib_crc(file, 0, data_end_at));
  EXPECT_EQ(load(file, footer + 25, 4), zlib_crc(file, summary_start, footer + 25));
  EXPECT_EQ(writer.messages_written(), 19u);
}

TEST(McapWriter, BuffersStayBoundedOverManyMessages) {
  MemorySink sink;
  McapWriterOptions options;
  options.chunk_size = 64 * 1024;
  McapWriter writer(sink, "long.mcap", options);
  const auto channel = writer.add_channel(0, "/a", "cdr");
  Bytes payload(1000);
  std::size_t buffers_after_first_chunks = 0;
  std::size_t summary_after_first_chunks = 0;
  std::uint32_t chunks_then = 0;
  for (std::uint64_t i = 0; i < 20000; ++i) {
    payload[i % payload.size()] = static_cast<unsigned char>(i);
    writer.write_message(channel, i, payload);
    if (i == 1000) {
      buffers_after_first_chunks = writer.chunk_buffer_bytes();
      summary_after_first_chunks = writer.summary_buffer_bytes();
      chunks_then = writer.chunks_written();
    }
  }
  // 20 MB written through 64 KiB chunks: the chunk buffers are what they were after 1 MB, under
  // four chunk sizes; the summary grows only by a Chunk Index record (under 128 bytes) a chunk.
  EXPECT_GT(writer.chunks_written(), 300u);
  EXPECT_EQ(writer.chunk_buffer_bytes(), buffers_after_first_chunks);
  EXPECT_LT(writer.chunk_buffer_bytes(), 4 * options.chunk_size);
  const std::size_t growth = writer.summary_buffer_bytes() - summary_after_first_chunks;
  EXPECT_LT(growth, 2 * 128 * (writer.chunks_written() - chunks_then));  // capacity doubles
  writer.finish();
}

TEST(McapWriter, AChunkBuiltApartIsPlacedAsTheWriterWouldHaveWrittenIt) {
  // The same messages: through write_message with a chunk closed after each pair, and as chunks
  // built apart (as on other threads) and placed by write_chunk.
  const Bytes payload(200, 0x33);
  const auto open = [&](McapSink& sink, std::uint16_t& a, std::uint16_t& b) {
    McapWriter writer(sink, "chunks.mcap");
    const auto schema = writer.add_schema("pkg/msg/T", "ros2msg", "uint8[] a\n");
    a = writer.add_channel(schema, "/a", "cdr");
    b = writer.add_channel(schema, "/b", "cdr");
    writer.write_message(b, 5, payload);
    writer.close_chunk();
    return writer;
  };
  MemorySink direct_sink, placed_sink;
  std::uint16_t a = 0, b = 0;
  McapWriter direct = open(direct_sink, a, b);
  McapWriter placed = open(placed_sink, a, b);
  McapChunk chunk;
  for (std::uint32_t pair = 0; pair < 3; ++pair) {
    direct.write_message(a, 10 + pair, payload);
    direct.write_message(b, 10 + pair, payload);
    direct.close_chunk();
    chunk.clear();
    chunk.add_message(a, pair, 10 + pair, 10 + pair, payload);
    chunk.add_message(b, pair + 1, 10 + pair, 10 + pair, payload);
    chunk.finish();
    placed.write_chunk(chunk);
  }
  direct.finish();
  placed.finish();
  EXPECT_EQ(placed.chunks_written(), 4u);
  EXPECT_EQ(placed.messages_written(), 7u);
  EXPECT_EQ(placed_sink.data, direct_sink.data);
}

// A distributed run (issue 47): a chunk built in one process is sent as bytes and placed by
// another. Placed from the bytes, it gives the file the chunk itself gives, index included.
TEST(McapChunk, AChunkSentAsBytesIsPlacedAsTheChunkItself) {
  const Bytes payload(300, 0x5a);
  MemorySink built_sink, sent_sink;
  McapWriter built(built_sink, "built.mcap");
  McapWriter sent(sent_sink, "sent.mcap");
  for (McapWriter* writer : {&built, &sent}) {
    const auto schema = writer->add_schema("pkg/msg/T", "ros2msg", "uint8[] a\n");
    writer->add_channel(schema, "/a", "cdr");
    writer->add_channel(schema, "/b", "cdr");
  }
  McapChunk chunk, received;
  std::string bytes;
  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    chunk.clear();
    chunk.add_message(2, frame, 1000 + frame, 1000 + frame, payload);
    chunk.add_message(1, frame, 900 + frame, 900 + frame, payload);
    chunk.finish();
    built.write_chunk(chunk);
    bytes.clear();
    chunk.append_finished(bytes);
    received.read_finished(bytes);
    EXPECT_TRUE(received.finished());
    EXPECT_EQ(received.records_size(), chunk.records_size());
    EXPECT_EQ(received.message_count(), 2u);
    sent.write_chunk(received);
  }
  built.finish();
  sent.finish();
  EXPECT_EQ(sent.messages_written(), 6u);
  EXPECT_EQ(sent_sink.data, built_sink.data);

  // Cut short or longer, or of another compression: refused; an unfinished chunk is not sent.
  EXPECT_THROW(received.read_finished(std::string_view(bytes).substr(0, bytes.size() - 1)), Error);
  EXPECT_THROW(received.read_finished(bytes + "x"), Error);
  EXPECT_THROW(received.read_finished(""), Error);
  McapChunk plain(McapCompression::none);
  try {
    plain.read_finished(bytes);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "MCAP chunk: a chunk of another compression read into this one");
  }
  chunk.clear();
  EXPECT_THROW(chunk.append_finished(bytes), Error);
  // Read back and cleared, a chunk builds and compresses as before.
  received.clear();
  received.add_message(1, 3, 5, 5, payload);
  received.finish();
  EXPECT_EQ(received.compression(), "zstd");
  EXPECT_LT(received.compressed_size(), received.records_size());
}

TEST(McapWriter, RefusesAChunkThatDoesNotContinueItsChannels) {
  MemorySink sink;
  McapWriter writer(sink, "gap.mcap");
  const auto channel = writer.add_channel(0, "/a", "cdr");
  const Bytes payload{1};
  McapChunk chunk;
  chunk.add_message(channel, 1, 0, 0, payload);  // message 0 was never written
  try {
    writer.write_chunk(chunk);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "gap.mcap: a chunk that was not finished");
  }
  chunk.finish();
  try {
    writer.write_chunk(chunk);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "gap.mcap: a chunk whose messages on channel 1 start at sequence 1, not 0");
  }
  EXPECT_THROW(chunk.add_message(channel, 2, 0, 0, payload), Error);  // finished
  McapChunk gap;
  gap.add_message(channel, 0, 0, 0, payload);
  EXPECT_THROW(gap.add_message(channel, 2, 0, 0, payload), Error);
}

TEST(McapWriter, RejectsMessagesOnUnknownChannelsAndWritesAfterFinish) {
  MemorySink sink;
  McapWriter writer(sink, "bad.mcap");
  const Bytes payload{1};
  try {
    writer.write_message(3, 0, payload);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "bad.mcap: a message on channel 3, which was never added");
  }
  EXPECT_THROW(static_cast<void>(writer.add_channel(2, "/x", "cdr")), Error);
  writer.finish();
  EXPECT_THROW(writer.write_message(1, 0, payload), Error);
}

TEST(McapWriter, FileAppearsOnlyWhenFinished) {
  const auto dir = std::filesystem::temp_directory_path() / "owsim_test_mcap_writer";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto path = dir / "flight.mcap";
  {
    McapWriter abandoned(path);
    abandoned.add_channel(0, "/a", "cdr");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(AtomicOutputFile::partial_path_for(path)));
  McapWriter writer(path);
  writer.finish();
  EXPECT_EQ(std::filesystem::file_size(path), writer.bytes_written());
  std::filesystem::remove_all(dir);
}

TEST(CdrWriter, AlignsToTheSizeOfEachPrimitiveAfterTheHeader) {
  CdrWriter cdr;
  cdr.u8(0xAB);
  cdr.f64(1.0);
  const Bytes uint8_then_float64{0x00, 0x01, 0x00, 0x00, 0xAB, 0, 0, 0, 0,    0,
                                 0,    0,    0,    0,    0,    0, 0, 0, 0xF0, 0x3F};
  EXPECT_EQ(Bytes(cdr.bytes().begin(), cdr.bytes().end()), uint8_then_float64);

  cdr.clear();
  cdr.u8(1);
  cdr.u16(0x0203);
  cdr.u8(4);
  cdr.u32(0x05060708);
  const Bytes mixed{0, 1, 0, 0, 1, 0, 0x03, 0x02, 4, 0, 0, 0, 0x08, 0x07, 0x06, 0x05};
  EXPECT_EQ(Bytes(cdr.bytes().begin(), cdr.bytes().end()), mixed);

  cdr.clear();
  cdr.string("map");
  cdr.boolean(true);
  cdr.sequence_size(2);
  const Bytes string_bool_sequence{0,   1, 0, 0, 4, 0, 0, 0, 'm', 'a',
                                   'p', 0, 1, 0, 0, 0, 2, 0, 0,   0};
  EXPECT_EQ(Bytes(cdr.bytes().begin(), cdr.bytes().end()), string_bool_sequence);
  EXPECT_THROW(cdr.string(std::string_view("a\0b", 3)), Error);
}

TEST(Ros2Messages, NavSatFixFieldsSitAtTheirAlignedOffsets) {
  ros2::NavSatFix fix;
  fix.header.stamp = {12, 34};
  fix.header.frame_id = "map";
  fix.status.status = ros2::NavSatStatus::kStatusFix;
  fix.status.service = ros2::NavSatStatus::kServiceGps;
  fix.latitude = 47.5;
  fix.position_covariance_type = ros2::NavSatFix::kCovarianceTypeKnown;
  CdrWriter cdr;
  ros2::serialize(fix, cdr);
  const auto bytes = cdr.bytes();
  // After the header (4): sec 0, nanosec 4, frame_id 8..15, status 16, service 18, latitude 24,
  // longitude 32, altitude 40, covariance 48..119, covariance type 120.
  ASSERT_EQ(bytes.size(), 4u + 121u);
  EXPECT_EQ(load(Bytes(bytes.begin(), bytes.end()), 4 + 4, 4), 34u);
  EXPECT_EQ(bytes[4 + 16], 0);
  EXPECT_EQ(bytes[4 + 17], 0);  // padding
  EXPECT_EQ(bytes[4 + 18], 1);
  EXPECT_EQ(load(Bytes(bytes.begin(), bytes.end()), 4 + 24, 8), 0x4047C00000000000u);
  EXPECT_EQ(bytes[4 + 120], 3);
}

TEST(Ros2Messages, LidarPointCloudLaysOutFortyBytePoints) {
  const std::vector<ros2::LidarPoint> points{{1.5, -2, 3, 0.25f, 7, 2, 14, 10.125}};
  Bytes data;
  ros2::pack_lidar_points(points, data);
  ASSERT_EQ(data.size(), 40u);
  EXPECT_EQ(load(data, 0, 8), 0x3FF8000000000000u);
  EXPECT_EQ(load(data, 24, 4), 0x3E800000u);
  EXPECT_EQ(load(data, 28, 2), 7u);
  EXPECT_EQ(data[30], 2);
  EXPECT_EQ(data[31], 14);
  EXPECT_EQ(load(data, 32, 8), 0x4024400000000000u);
  const ros2::PointCloud2 cloud = ros2::lidar_point_cloud({{1, 2}, "map"}, data);
  EXPECT_EQ(cloud.width, 1u);
  EXPECT_EQ(cloud.row_step, 40u);
  ASSERT_EQ(cloud.fields.size(), 8u);
  EXPECT_EQ(cloud.fields[7].name, "time");
  EXPECT_EQ(cloud.fields[7].offset, 32u);
}

TEST(Ros2Time, SplitsNanosecondsIntoSecondsAndNanoseconds) {
  EXPECT_EQ(ros2::time_from_nanoseconds(1'500'000'000).sec, 1);
  EXPECT_EQ(ros2::time_from_nanoseconds(1'500'000'000).nanosec, 500'000'000u);
  EXPECT_EQ(ros2::time_from_nanoseconds(-1).sec, -1);
  EXPECT_EQ(ros2::time_from_nanoseconds(-1).nanosec, 999'999'999u);
  EXPECT_THROW(static_cast<void>(ros2::time_from_nanoseconds(std::int64_t{1} << 62)), Error);
}

std::vector<std::string> delimiters(const std::string& schema) {
  std::vector<std::string> names;
  const std::string rule = std::string(80, '=') + "\nMSG: ";
  for (std::size_t at = schema.find(rule); at != std::string::npos;
       at = schema.find(rule, at + 1)) {
    const std::size_t begin = at + rule.size();
    names.push_back(schema.substr(begin, schema.find('\n', begin) - begin));
  }
  return names;
}

TEST(Ros2Schemas, DependenciesFollowOnceDepthFirstInSortedOrderAsRosbag2WritesThem) {
  const std::string cloud = ros2::ros2msg_schema(ros2::kPointCloud2Type);
  EXPECT_EQ(cloud.rfind("# This message holds a collection of N-dimensional points", 0), 0u);
  EXPECT_EQ(delimiters(cloud),
            (std::vector<std::string>{"sensor_msgs/PointField", "std_msgs/Header",
                                      "builtin_interfaces/Time"}));
  // The .msg text ends with its newline; the delimiter adds one more before the rule.
  EXPECT_NE(cloud.find("bool is_dense        # True if there are no invalid points\n\n" +
                       std::string(80, '=') + "\nMSG: sensor_msgs/PointField\n"),
            std::string::npos);
  EXPECT_EQ(delimiters(ros2::ros2msg_schema(ros2::kTfMessageType)),
            (std::vector<std::string>{"geometry_msgs/TransformStamped", "geometry_msgs/Transform",
                                      "geometry_msgs/Quaternion", "geometry_msgs/Vector3",
                                      "std_msgs/Header", "builtin_interfaces/Time"}));
  EXPECT_EQ(delimiters(ros2::ros2msg_schema(ros2::kNavSatFixType)),
            (std::vector<std::string>{"sensor_msgs/NavSatStatus", "std_msgs/Header",
                                      "builtin_interfaces/Time"}));
  EXPECT_EQ(
      delimiters(ros2::ros2msg_schema(ros2::kMarkerArrayType)),
      (std::vector<std::string>{
          "visualization_msgs/Marker", "builtin_interfaces/Duration", "geometry_msgs/Point",
          "geometry_msgs/Pose", "geometry_msgs/Quaternion", "geometry_msgs/Vector3",
          "sensor_msgs/CompressedImage", "std_msgs/Header", "builtin_interfaces/Time",
          "std_msgs/ColorRGBA", "visualization_msgs/MeshFile", "visualization_msgs/UVCoordinate"}));
  EXPECT_THROW(static_cast<void>(ros2::ros2msg_schema("sensor_msgs/msg/Image")), Error);
  EXPECT_THROW(static_cast<void>(ros2::ros2msg_schema("PointCloud2")), Error);
}

TEST(Ros2Qos, LatchedChannelsOfferTransientLocalDurability) {
  EXPECT_EQ(ros2::offered_qos_profiles(true),
            "- history: 1\n  depth: 1\n  reliability: 1\n  durability: 1\n  deadline:\n"
            "    sec: 0\n    nsec: 0\n  lifespan:\n    sec: 0\n    nsec: 0\n  liveliness: 1\n"
            "  liveliness_lease_duration:\n    sec: 0\n    nsec: 0\n"
            "  avoid_ros_namespace_conventions: false");
  EXPECT_NE(ros2::offered_qos_profiles(false).find("  depth: 10\n"), std::string::npos);
  EXPECT_NE(ros2::offered_qos_profiles(false).find("  durability: 2\n"), std::string::npos);
  const auto metadata = ros2::channel_metadata(true);
  ASSERT_EQ(metadata.size(), 1u);
  EXPECT_EQ(metadata[0].first, "offered_qos_profiles");
}

}  // namespace
}  // namespace owsim
