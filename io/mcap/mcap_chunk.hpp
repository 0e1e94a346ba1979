#pragma once
// One Chunk of an MCAP file (https://mcap.dev/spec) built apart from the file: its records
// (Schema, Channel, Message) in the order given; finish() compresses them and lays out the Chunk
// record followed by one Message Index record per channel with messages in it (ascending channel
// id). Those bytes depend on nothing before them in the file, so chunks can be built on any thread
// (each McapChunk its own, with its own zstd context) and McapWriter::write_chunk()
// (io/mcap/mcap_writer.hpp) places them in order, computing their Chunk Index from where they
// land. Reused chunk after chunk (clear()): it allocates only while its buffers grow. A finished
// chunk also travels between the processes of a distributed run (append_finished, read_finished).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/mcap/mcap_records.hpp"

namespace owsim {

enum class McapCompression { zstd, none };

class McapChunk {
 public:
  // The messages of one channel in the chunk.
  struct ChannelMessages {
    std::uint16_t channel_id = 0;
    std::uint32_t first_sequence = 0;
    std::uint64_t count = 0;
  };

  explicit McapChunk(McapCompression compression = McapCompression::zstd, int zstd_level = 1);
  McapChunk(McapChunk&&) noexcept;
  McapChunk& operator=(McapChunk&&) noexcept;
  ~McapChunk();

  // Empty again, for the next chunk.
  void clear();
  // A Schema or Channel record (the writer puts its own into its first chunk).
  void add_schema(std::uint16_t id, std::string_view name, std::string_view encoding,
                  std::string_view data);
  void add_channel(std::uint16_t id, std::uint16_t schema_id, std::string_view topic,
                   std::string_view message_encoding,
                   const std::vector<std::pair<std::string, std::string>>& metadata);
  // A Message record; a channel's messages must come with consecutive sequence numbers.
  // Throws owsim::Error for channel 0 or a gap in a channel's sequence.
  void add_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                   std::uint64_t publish_time_ns, std::span<const unsigned char> data);

  // Compresses the records and lays out the bytes below; nothing may be added afterwards (until
  // clear()). Throws owsim::Error if compression fails.
  void finish();

  [[nodiscard]] bool empty() const { return records_size() == 0; }
  [[nodiscard]] bool finished() const { return finished_; }
  // The records' bytes, uncompressed.
  [[nodiscard]] std::size_t records_size() const {
    return finished_ ? uncompressed_size_ : records_.size();
  }
  [[nodiscard]] bool has_messages() const { return message_count_ > 0; }
  [[nodiscard]] std::uint64_t message_count() const { return message_count_; }
  [[nodiscard]] std::uint64_t start_time() const { return start_time_; }
  [[nodiscard]] std::uint64_t end_time() const { return end_time_; }

  // After finish(): the Chunk record and its Message Index records, their CRC-32, where the
  // message indexes start (from the chunk record's first byte), and the channels with messages.
  [[nodiscard]] std::span<const unsigned char> bytes() const { return bytes_; }
  [[nodiscard]] std::uint32_t crc() const { return crc_; }
  [[nodiscard]] std::size_t chunk_record_size() const { return chunk_record_size_; }
  [[nodiscard]] std::uint64_t compressed_size() const { return compressed_size_; }
  [[nodiscard]] std::string_view compression() const;
  // Each channel's Message Index offset from the chunk record's first byte, ascending channel id.
  [[nodiscard]] const std::vector<std::pair<std::uint16_t, std::uint64_t>>& message_index_offsets()
      const {
    return message_index_offsets_;
  }
  [[nodiscard]] const std::vector<ChannelMessages>& channels() const { return channels_; }

  // A finished chunk as bytes: its laid-out bytes and what McapWriter::write_chunk needs besides,
  // for a process that places chunks another one built (distributed/distributed_run.hpp). Both
  // ends are the same owsim build: fields in a fixed order, native byte order, not a file format.
  // Throws owsim::Error if the chunk is not finished.
  void append_finished(std::string& out) const;
  // Becomes the finished chunk append_finished wrote into `bytes` (the whole of them): ready for
  // McapWriter::write_chunk, nothing may be added until clear(). Throws owsim::Error for bytes of
  // another size or a chunk of another compression than this one's.
  void read_finished(std::string_view bytes);

  // Bytes held (records, compressed copy, laid-out bytes, message index entries).
  [[nodiscard]] std::size_t buffer_bytes() const;

 private:
  class Compressor;
  struct ChannelEntries {
    std::uint32_t first_sequence = 0;
    std::uint64_t count = 0;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> entries;  // log time, offset
  };

  McapCompression compression_;
  std::unique_ptr<Compressor> compressor_;
  mcap::Bytes records_;
  mcap::Bytes bytes_;
  std::vector<ChannelEntries> entries_;  // channel id − 1
  std::vector<ChannelMessages> channels_;
  std::vector<std::pair<std::uint16_t, std::uint64_t>> message_index_offsets_;
  std::uint64_t message_count_ = 0;
  std::uint64_t start_time_ = 0;
  std::uint64_t end_time_ = 0;
  std::uint32_t crc_ = 0;
  std::size_t chunk_record_size_ = 0;
  std::uint64_t compressed_size_ = 0;
  std::size_t uncompressed_size_ = 0;  // records_size() once finished
  bool finished_ = false;
};

}  // namespace owsim
