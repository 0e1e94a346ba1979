#pragma once
// The records of an MCAP file (MCAP format specification, major version 0,
// https://mcap.dev/spec): each an opcode byte, a uint64 length of its content and the content,
// integers little-endian, a String a uint32 byte length and the bytes, a Map a uint32 byte length
// and its key-value pairs. append_*() appends one whole record to `out`; the streaming writer
// (io/mcap/mcap_writer.hpp) decides where each goes.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace owsim::mcap {

using Bytes = std::vector<unsigned char>;

inline constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
inline constexpr std::size_t kRecordPrefixBytes = 9;  // opcode and uint64 length

enum class Opcode : std::uint8_t {
  header = 0x01,
  footer = 0x02,
  schema = 0x03,
  channel = 0x04,
  message = 0x05,
  chunk = 0x06,
  message_index = 0x07,
  chunk_index = 0x08,
  statistics = 0x0B,
  summary_offset = 0x0E,
  data_end = 0x0F,
};

// CRC-32 (ISO-HDLC, zlib's) of `bytes` continuing `crc` (0 to start).
[[nodiscard]] std::uint32_t crc32(std::uint32_t crc, std::span<const unsigned char> bytes);
// The CRC-32 of A then B from the CRC of A, the CRC of B and B's length (zlib's crc32_combine).
[[nodiscard]] std::uint32_t crc32_combine(std::uint32_t crc_a, std::uint32_t crc_b,
                                          std::uint64_t length_b);

void append_header(Bytes& out, std::string_view profile, std::string_view library);
void append_schema(Bytes& out, std::uint16_t id, std::string_view name, std::string_view encoding,
                   std::string_view data);
void append_channel(Bytes& out, std::uint16_t id, std::uint16_t schema_id, std::string_view topic,
                    std::string_view message_encoding,
                    const std::vector<std::pair<std::string, std::string>>& metadata);
void append_message(Bytes& out, std::uint16_t channel_id, std::uint32_t sequence,
                    std::uint64_t log_time, std::uint64_t publish_time,
                    std::span<const unsigned char> data);

// A chunk's fields but its records, which follow the prefix (append_chunk_prefix() counts them in
// the lengths without holding them).
struct ChunkFields {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string_view compression;    // "zstd" or "" (none)
  std::uint64_t records_size = 0;  // the records as stored (compressed)
};
void append_chunk_prefix(Bytes& out, const ChunkFields& chunk);

// One message index: the log time and the offset in the chunk's uncompressed records of each
// message of a channel.
void append_message_index(Bytes& out, std::uint16_t channel_id,
                          std::span<const std::pair<std::uint64_t, std::uint64_t>> entries);

struct ChunkIndexFields {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;  // the whole record
  std::vector<std::pair<std::uint16_t, std::uint64_t>> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string_view compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};
void append_chunk_index(Bytes& out, const ChunkIndexFields& index);

struct StatisticsFields {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::vector<std::pair<std::uint16_t, std::uint64_t>> channel_message_counts;
};
void append_statistics(Bytes& out, const StatisticsFields& statistics);

void append_summary_offset(Bytes& out, Opcode group_opcode, std::uint64_t group_start,
                           std::uint64_t group_length);
void append_data_end(Bytes& out, std::uint32_t data_section_crc);
// The footer up to its summary_crc (what that CRC covers last), then append_footer_crc().
void append_footer_fields(Bytes& out, std::uint64_t summary_start,
                          std::uint64_t summary_offset_start);
void append_footer_crc(Bytes& out, std::uint32_t summary_crc);

}  // namespace owsim::mcap
