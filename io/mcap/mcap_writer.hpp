#pragma once
// flight.mcap's writer: an MCAP file (https://mcap.dev/spec, io/mcap/mcap_records.hpp) written
// streaming, record by record, with the layout readers index and seek by:
//   magic, Header (profile, library "owsim <version>"),
//   Chunks — Schema, Channel and Message records in the order given, compressed with zstd (or
//     not), each closed once its records reach `chunk_size` uncompressed bytes, with the log-time
//     range of its messages and the CRC-32 of its uncompressed records — each followed by one
//     Message Index per channel with messages in it (ascending channel id),
//   Data End (CRC-32 of every byte before it),
//   summary: every Schema, every Channel, Statistics, one Chunk Index per chunk,
//   one Summary Offset per group of the summary, Footer (summary CRC-32), magic.
// Memory holds one chunk's records (and their compressed copy) and, per chunk, one Chunk Index
// record of some 100 bytes for the summary: flat in the file's length otherwise. Chunks built
// elsewhere (io/mcap/mcap_chunk.hpp, on other threads) are placed whole by write_chunk().
// The bytes depend only on the calls made (no clock, no threads): the same calls give the same
// file. Output goes through an AtomicOutputFile (nothing under the final name before finish()) or
// into a sink the caller gives. Errors throw owsim::Error naming the file.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/files/atomic_output_file.hpp"
#include "io/mcap/mcap_chunk.hpp"
#include "io/mcap/mcap_records.hpp"

namespace owsim {

struct McapWriterOptions {
  std::string profile = "ros2";
  std::string library;                            // empty: "owsim <version>"
  std::size_t chunk_size = std::size_t{1} << 20;  // uncompressed record bytes that close a chunk
  McapCompression compression = McapCompression::zstd;
  int zstd_level = 1;  // fast: a flight's point clouds stream through it
  AtomicOutputOptions file;
};

// Where a McapWriter's bytes go when not to a file of its own.
class McapSink {
 public:
  virtual ~McapSink() = default;
  virtual void write(std::span<const unsigned char> bytes) = 0;
  // After the last byte (McapWriter::finish()).
  virtual void finish() {}
};

// Metadata of a channel: key-value pairs, written in the order given.
using McapMetadata = std::vector<std::pair<std::string, std::string>>;

class McapWriter {
 public:
  // Writes the magic and the Header into `<final_path>.partial`; finish() renames it.
  explicit McapWriter(std::filesystem::path final_path, McapWriterOptions options = {});
  // The same into `sink`, which must outlive the writer; `name` names it in errors.
  McapWriter(McapSink& sink, std::string name, McapWriterOptions options = {});
  McapWriter(McapWriter&&) noexcept;
  McapWriter& operator=(McapWriter&&) = delete;
  // Without finish(), a file of its own is removed (AtomicOutputFile); a sink is left as it is.
  ~McapWriter();

  // Registers a schema (ids 1, 2, …). `encoding` "ros2msg" for ROS 2 .msg text.
  std::uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data);
  // Registers a channel (ids 1, 2, …) of a schema this writer returned (0: none). `metadata` as
  // ROS 2's ros2::channel_metadata() gives (offered_qos_profiles: latched or not).
  std::uint16_t add_channel(std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding, const McapMetadata& metadata = {});
  // A message on a channel this writer returned; times in nanoseconds (publish time = log time
  // when not given). Its sequence is the count of earlier messages on the channel.
  void write_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                     std::span<const unsigned char> data) {
    write_message(channel_id, log_time_ns, log_time_ns, data);
  }
  void write_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                     std::uint64_t publish_time_ns, std::span<const unsigned char> data);
  // Closes the open chunk (if it holds records), then writes `chunk` (finished, with messages on
  // channels this writer added only, each channel's first sequence the count of its earlier
  // messages) as the next chunk, whatever its size. Its compression is its own.
  void write_chunk(const McapChunk& chunk);
  // Closes the open chunk now (if it holds records), so the next message starts a new one.
  void close_chunk();
  // Closes the last chunk, writes Data End, the summary and the footer, and renames the file to
  // its final name (or finishes the sink). Nothing may be written afterwards.
  void finish();

  [[nodiscard]] std::uint64_t messages_written() const { return message_count_; }
  [[nodiscard]] std::uint32_t chunks_written() const { return chunk_count_; }
  [[nodiscard]] std::uint64_t bytes_written() const { return offset_; }
  // Bytes the writer holds for the chunk being filled (records, compressed copy, message indexes)
  // — bounded by the chunk size and the largest message — and for the summary (grows by one
  // Chunk Index record a chunk).
  [[nodiscard]] std::size_t chunk_buffer_bytes() const;
  [[nodiscard]] std::size_t summary_buffer_bytes() const;

 private:
  class FileSink;

  McapWriter(std::unique_ptr<McapSink> owned, McapSink* borrowed, std::string name,
             const McapWriterOptions& options);
  void emit(std::span<const unsigned char> bytes);
  void place(const McapChunk& chunk);
  void require_open(std::string_view operation) const;
  [[noreturn]] void fail(std::string_view problem) const;

  std::unique_ptr<McapSink> owned_sink_;
  McapSink* sink_;
  std::string name_;
  McapWriterOptions options_;
  std::uint64_t offset_ = 0;   // bytes written
  std::uint32_t crc_ = 0;      // of the data section, then of the summary
  McapChunk chunk_;            // the open chunk
  mcap::Bytes record_;         // a record being written (data end, summary), reused
  mcap::Bytes schemas_;        // the summary's Schema records
  mcap::Bytes channels_;       // the summary's Channel records
  mcap::Bytes chunk_indexes_;  // the summary's Chunk Index records
  std::uint16_t schema_count_ = 0;
  std::vector<std::uint64_t> channel_messages_;  // by channel id − 1: messages written
  std::uint64_t message_count_ = 0;
  std::uint64_t start_time_ = 0;
  std::uint64_t end_time_ = 0;
  std::uint32_t chunk_count_ = 0;
  bool finished_ = false;
};

}  // namespace owsim
