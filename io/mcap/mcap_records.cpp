#include "io/mcap/mcap_records.hpp"

#include <zlib.h>

#include <limits>
#include <string>

#include "geometry/error.hpp"
#include "io/files/little_endian.hpp"

namespace owsim::mcap {
namespace {

template <typename UInt>
void put(Bytes& out, UInt value) {
  unsigned char bytes[sizeof(UInt)];
  store_little_endian(value, bytes);
  out.insert(out.end(), bytes, bytes + sizeof(UInt));
}

void put_bytes(Bytes& out, std::string_view bytes) {
  out.insert(out.end(), bytes.begin(), bytes.end());
}

std::uint32_t length32(std::size_t size, std::string_view what) {
  if (size > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("MCAP " + std::string(what) + " of " + std::to_string(size) +
                " bytes is longer than a uint32 length can say");
  }
  return static_cast<std::uint32_t>(size);
}

void put_string(Bytes& out, std::string_view text) {
  put(out, length32(text.size(), "string"));
  put_bytes(out, text);
}

// The opcode and a length to fill in by end_record(); returns where the length goes.
std::size_t begin_record(Bytes& out, Opcode opcode) {
  out.push_back(static_cast<unsigned char>(opcode));
  const std::size_t length_at = out.size();
  put(out, std::uint64_t{0});
  return length_at;
}

void end_record(Bytes& out, std::size_t length_at) {
  store_little_endian(static_cast<std::uint64_t>(out.size() - length_at - 8),
                      out.data() + length_at);
}

// A Map or Array: a uint32 byte length to fill in by end_sized().
std::size_t begin_sized(Bytes& out) {
  const std::size_t length_at = out.size();
  put(out, std::uint32_t{0});
  return length_at;
}

void end_sized(Bytes& out, std::size_t length_at, std::string_view what) {
  store_little_endian(length32(out.size() - length_at - 4, what), out.data() + length_at);
}

void put_id_counts(Bytes& out, std::span<const std::pair<std::uint16_t, std::uint64_t>> map) {
  const std::size_t at = begin_sized(out);
  for (const auto& entry : map) {
    put(out, entry.first);
    put(out, entry.second);
  }
  end_sized(out, at, "map");
}

}  // namespace

std::uint32_t crc32(std::uint32_t crc, std::span<const unsigned char> bytes) {
  return static_cast<std::uint32_t>(::crc32_z(crc, bytes.data(), bytes.size()));
}

std::uint32_t crc32_combine(std::uint32_t crc_a, std::uint32_t crc_b, std::uint64_t length_b) {
  static_assert(sizeof(z_off_t) >= 8, "zlib's offsets must hold a file's length");
  return static_cast<std::uint32_t>(::crc32_combine(crc_a, crc_b, static_cast<z_off_t>(length_b)));
}

void append_header(Bytes& out, std::string_view profile, std::string_view library) {
  const std::size_t at = begin_record(out, Opcode::header);
  put_string(out, profile);
  put_string(out, library);
  end_record(out, at);
}

void append_schema(Bytes& out, std::uint16_t id, std::string_view name, std::string_view encoding,
                   std::string_view data) {
  const std::size_t at = begin_record(out, Opcode::schema);
  put(out, id);
  put_string(out, name);
  put_string(out, encoding);
  put_string(out, data);  // uint32 length-prefixed bytes
  end_record(out, at);
}

void append_channel(Bytes& out, std::uint16_t id, std::uint16_t schema_id, std::string_view topic,
                    std::string_view message_encoding,
                    const std::vector<std::pair<std::string, std::string>>& metadata) {
  const std::size_t at = begin_record(out, Opcode::channel);
  put(out, id);
  put(out, schema_id);
  put_string(out, topic);
  put_string(out, message_encoding);
  const std::size_t map_at = begin_sized(out);
  for (const auto& entry : metadata) {
    put_string(out, entry.first);
    put_string(out, entry.second);
  }
  end_sized(out, map_at, "map");
  end_record(out, at);
}

void append_message(Bytes& out, std::uint16_t channel_id, std::uint32_t sequence,
                    std::uint64_t log_time, std::uint64_t publish_time,
                    std::span<const unsigned char> data) {
  const std::size_t at = begin_record(out, Opcode::message);
  put(out, channel_id);
  put(out, sequence);
  put(out, log_time);
  put(out, publish_time);
  out.insert(out.end(), data.begin(), data.end());
  end_record(out, at);
}

void append_chunk_prefix(Bytes& out, const ChunkFields& chunk) {
  out.push_back(static_cast<unsigned char>(Opcode::chunk));
  put(out, std::uint64_t{8 + 8 + 8 + 4 + 4 + chunk.compression.size() + 8 + chunk.records_size});
  put(out, chunk.message_start_time);
  put(out, chunk.message_end_time);
  put(out, chunk.uncompressed_size);
  put(out, chunk.uncompressed_crc);
  put_string(out, chunk.compression);
  put(out, chunk.records_size);
}

void append_message_index(Bytes& out, std::uint16_t channel_id,
                          std::span<const std::pair<std::uint64_t, std::uint64_t>> entries) {
  const std::size_t at = begin_record(out, Opcode::message_index);
  put(out, channel_id);
  const std::size_t array_at = begin_sized(out);
  for (const auto& entry : entries) {
    put(out, entry.first);
    put(out, entry.second);
  }
  end_sized(out, array_at, "message index");
  end_record(out, at);
}

void append_chunk_index(Bytes& out, const ChunkIndexFields& index) {
  const std::size_t at = begin_record(out, Opcode::chunk_index);
  put(out, index.message_start_time);
  put(out, index.message_end_time);
  put(out, index.chunk_start_offset);
  put(out, index.chunk_length);
  put_id_counts(out, index.message_index_offsets);
  put(out, index.message_index_length);
  put_string(out, index.compression);
  put(out, index.compressed_size);
  put(out, index.uncompressed_size);
  end_record(out, at);
}

void append_statistics(Bytes& out, const StatisticsFields& statistics) {
  const std::size_t at = begin_record(out, Opcode::statistics);
  put(out, statistics.message_count);
  put(out, statistics.schema_count);
  put(out, statistics.channel_count);
  put(out, std::uint32_t{0});  // attachment_count
  put(out, std::uint32_t{0});  // metadata_count
  put(out, statistics.chunk_count);
  put(out, statistics.message_start_time);
  put(out, statistics.message_end_time);
  put_id_counts(out, statistics.channel_message_counts);
  end_record(out, at);
}

void append_summary_offset(Bytes& out, Opcode group_opcode, std::uint64_t group_start,
                           std::uint64_t group_length) {
  const std::size_t at = begin_record(out, Opcode::summary_offset);
  out.push_back(static_cast<unsigned char>(group_opcode));
  put(out, group_start);
  put(out, group_length);
  end_record(out, at);
}

void append_data_end(Bytes& out, std::uint32_t data_section_crc) {
  const std::size_t at = begin_record(out, Opcode::data_end);
  put(out, data_section_crc);
  end_record(out, at);
}

void append_footer_fields(Bytes& out, std::uint64_t summary_start,
                          std::uint64_t summary_offset_start) {
  out.push_back(static_cast<unsigned char>(Opcode::footer));
  put(out, std::uint64_t{8 + 8 + 4});
  put(out, summary_start);
  put(out, summary_offset_start);
}

void append_footer_crc(Bytes& out, std::uint32_t summary_crc) { put(out, summary_crc); }

}  // namespace owsim::mcap
