#include "io/mcap/mcap_chunk.hpp"

#include <zstd.h>

#include <algorithm>
#include <cstring>

#include "geometry/error.hpp"
#include "io/files/host_bytes.hpp"

namespace owsim {

// zstd's compression context, reused from chunk to chunk.
class McapChunk::Compressor {
 public:
  explicit Compressor(int level) : context_(ZSTD_createCCtx()), level_(level) {
    if (context_ == nullptr) throw Error("cannot create a zstd compression context");
  }
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;
  ~Compressor() { ZSTD_freeCCtx(context_); }

  // Compresses `records` to `out` (at least ZSTD_compressBound bytes); returns the size.
  std::size_t compress(std::span<const unsigned char> records, std::span<unsigned char> out) {
    const std::size_t size =
        ZSTD_compressCCtx(context_, out.data(), out.size(), records.data(), records.size(), level_);
    if (ZSTD_isError(size)) {
      throw Error(std::string("zstd compression failed: ") + ZSTD_getErrorName(size));
    }
    return size;
  }

 private:
  ZSTD_CCtx* context_;
  int level_;
};

McapChunk::McapChunk(McapCompression compression, int zstd_level) : compression_(compression) {
  if (compression_ == McapCompression::zstd) compressor_ = std::make_unique<Compressor>(zstd_level);
}

McapChunk::McapChunk(McapChunk&&) noexcept = default;
McapChunk& McapChunk::operator=(McapChunk&&) noexcept = default;
McapChunk::~McapChunk() = default;

std::string_view McapChunk::compression() const {
  return compression_ == McapCompression::zstd ? "zstd" : "";
}

void McapChunk::clear() {
  records_.clear();
  bytes_.clear();
  for (ChannelEntries& channel : entries_) {
    channel.count = 0;
    channel.entries.clear();
  }
  channels_.clear();
  message_index_offsets_.clear();
  message_count_ = 0;
  start_time_ = end_time_ = 0;
  crc_ = 0;
  chunk_record_size_ = 0;
  compressed_size_ = 0;
  uncompressed_size_ = 0;
  finished_ = false;
}

void McapChunk::add_schema(std::uint16_t id, std::string_view name, std::string_view encoding,
                           std::string_view data) {
  if (finished_) throw Error("MCAP chunk: a schema after the chunk was finished");
  mcap::append_schema(records_, id, name, encoding, data);
}

void McapChunk::add_channel(std::uint16_t id, std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding,
                            const std::vector<std::pair<std::string, std::string>>& metadata) {
  if (finished_) throw Error("MCAP chunk: a channel after the chunk was finished");
  mcap::append_channel(records_, id, schema_id, topic, message_encoding, metadata);
}

void McapChunk::add_message(std::uint16_t channel_id, std::uint32_t sequence,
                            std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
                            std::span<const unsigned char> data) {
  if (finished_) throw Error("MCAP chunk: a message after the chunk was finished");
  if (channel_id == 0) throw Error("MCAP chunk: a message on channel 0");
  if (entries_.size() < channel_id) entries_.resize(channel_id);
  ChannelEntries& channel = entries_[channel_id - 1];
  if (channel.count == 0) {
    channel.first_sequence = sequence;
  } else if (sequence != static_cast<std::uint32_t>(channel.first_sequence + channel.count)) {
    throw Error("MCAP chunk: message " + std::to_string(sequence) + " on channel " +
                std::to_string(channel_id) + " does not follow message " +
                std::to_string(channel.first_sequence + channel.count - 1));
  }
  channel.entries.emplace_back(log_time_ns, records_.size());
  ++channel.count;
  mcap::append_message(records_, channel_id, sequence, log_time_ns, publish_time_ns, data);
  if (message_count_ == 0) start_time_ = end_time_ = log_time_ns;
  start_time_ = std::min(start_time_, log_time_ns);
  end_time_ = std::max(end_time_, log_time_ns);
  ++message_count_;
}

void McapChunk::finish() {
  if (finished_) throw Error("MCAP chunk: finished twice");
  const std::uint32_t records_crc = mcap::crc32(0, records_);
  // The prefix's length does not depend on the stored size: lay it out once to learn it, store the
  // records after it, then lay it out again with their size.
  mcap::ChunkFields fields{start_time_, end_time_, records_.size(), records_crc, compression(), 0};
  bytes_.clear();
  mcap::append_chunk_prefix(bytes_, fields);
  const std::size_t prefix = bytes_.size();
  if (compressor_) {
    bytes_.resize(prefix + ZSTD_compressBound(records_.size()));
    fields.records_size =
        compressor_->compress(records_, std::span<unsigned char>(bytes_).subspan(prefix));
    bytes_.resize(prefix + fields.records_size);
  } else {
    bytes_.insert(bytes_.end(), records_.begin(), records_.end());
    fields.records_size = records_.size();
  }
  mcap::Bytes prefix_bytes;
  prefix_bytes.reserve(prefix);
  mcap::append_chunk_prefix(prefix_bytes, fields);
  std::memcpy(bytes_.data(), prefix_bytes.data(), prefix);
  chunk_record_size_ = bytes_.size();
  compressed_size_ = fields.records_size;

  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const ChannelEntries& channel = entries_[i];
    if (channel.count == 0) continue;
    const auto channel_id = static_cast<std::uint16_t>(i + 1);
    message_index_offsets_.emplace_back(channel_id, bytes_.size());
    channels_.push_back({channel_id, channel.first_sequence, channel.count});
    mcap::append_message_index(bytes_, channel_id, channel.entries);
  }
  crc_ = mcap::crc32(0, bytes_);
  uncompressed_size_ = records_.size();
  finished_ = true;
}

void McapChunk::append_finished(std::string& out) const {
  if (!finished_) throw Error("MCAP chunk: sent before it was finished");
  put_host_bytes(out, compression_);
  put_host_bytes(out, message_count_);
  put_host_bytes(out, start_time_);
  put_host_bytes(out, end_time_);
  put_host_bytes(out, crc_);
  put_host_bytes(out, static_cast<std::uint64_t>(chunk_record_size_));
  put_host_bytes(out, compressed_size_);
  put_host_bytes(out, static_cast<std::uint64_t>(uncompressed_size_));
  put_host_vector(out, channels_);
  put_host_bytes(out, static_cast<std::uint64_t>(message_index_offsets_.size()));
  for (const auto& [channel_id, offset] : message_index_offsets_) {
    put_host_bytes(out, channel_id);
    put_host_bytes(out, offset);
  }
  put_host_vector(out, bytes_);
}

void McapChunk::read_finished(std::string_view bytes) {
  clear();
  HostBytesReader in(bytes, "MCAP chunk: the bytes end inside a chunk");
  McapCompression compression = compression_;
  in.get(compression);
  // A chunk stays what it was made: the compression of the chunks it builds after clear().
  if (compression != compression_) {
    throw Error("MCAP chunk: a chunk of another compression read into this one");
  }
  in.get(message_count_);
  in.get(start_time_);
  in.get(end_time_);
  in.get(crc_);
  std::uint64_t size = 0;
  in.get(size);
  chunk_record_size_ = static_cast<std::size_t>(size);
  in.get(compressed_size_);
  in.get(size);
  uncompressed_size_ = static_cast<std::size_t>(size);
  in.get_vector(channels_);
  std::uint64_t indexes = 0;
  in.get(indexes);
  for (std::uint64_t i = 0; i < indexes; ++i) {
    std::uint16_t channel_id = 0;
    std::uint64_t offset = 0;
    in.get(channel_id);
    in.get(offset);
    message_index_offsets_.emplace_back(channel_id, offset);
  }
  in.get_vector(bytes_);
  if (!in.empty()) throw Error("MCAP chunk: bytes after the chunk");
  finished_ = true;
}

std::size_t McapChunk::buffer_bytes() const {
  std::size_t bytes = records_.capacity() + bytes_.capacity();
  for (const ChannelEntries& channel : entries_) {
    bytes += channel.entries.capacity() * sizeof(channel.entries[0]);
  }
  return bytes;
}

}  // namespace owsim
