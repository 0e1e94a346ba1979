#include "io/mcap/mcap_writer.hpp"

#include <zstd.h>

#include <algorithm>
#include <limits>
#include <utility>

#include "geometry/error.hpp"
#include "owsim/version.hpp"

namespace owsim {

// zstd's compression context, reused from chunk to chunk, and its output buffer.
class McapWriter::Compressor {
 public:
  explicit Compressor(int level) : context_(ZSTD_createCCtx()), level_(level) {
    if (context_ == nullptr) throw Error("cannot create a zstd compression context");
  }
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;
  ~Compressor() { ZSTD_freeCCtx(context_); }

  // The compressed bytes of `records`, valid until the next call.
  std::span<const unsigned char> compress(std::span<const unsigned char> records) {
    output_.resize(ZSTD_compressBound(records.size()));
    const std::size_t size = ZSTD_compressCCtx(context_, output_.data(), output_.size(),
                                               records.data(), records.size(), level_);
    if (ZSTD_isError(size)) {
      throw Error(std::string("zstd compression failed: ") + ZSTD_getErrorName(size));
    }
    return std::span<const unsigned char>(output_).first(size);
  }
  [[nodiscard]] std::size_t capacity() const { return output_.capacity(); }

 private:
  ZSTD_CCtx* context_;
  int level_;
  mcap::Bytes output_;
};

class McapWriter::FileSink final : public McapSink {
 public:
  FileSink(std::filesystem::path final_path, AtomicOutputOptions options)
      : file_(std::move(final_path), options) {}
  void write(std::span<const unsigned char> bytes) override {
    file_.write(bytes.data(), bytes.size());
  }
  void finish() override { file_.commit(); }

 private:
  AtomicOutputFile file_;
};

McapWriter::McapWriter(std::filesystem::path final_path, McapWriterOptions options)
    : McapWriter(std::make_unique<FileSink>(final_path, options.file), nullptr, final_path.string(),
                 options) {}

McapWriter::McapWriter(McapSink& sink, std::string name, McapWriterOptions options)
    : McapWriter(nullptr, &sink, std::move(name), options) {}

McapWriter::McapWriter(std::unique_ptr<McapSink> owned, McapSink* borrowed, std::string name,
                       const McapWriterOptions& options)
    : owned_sink_(std::move(owned)),
      sink_(owned_sink_ ? owned_sink_.get() : borrowed),
      name_(std::move(name)),
      options_(options) {
  if (options_.chunk_size == 0) fail("the chunk size must be positive");
  if (options_.compression == McapCompression::zstd) {
    compressor_ = std::make_unique<Compressor>(options_.zstd_level);
  }
  if (options_.library.empty()) options_.library = std::string("owsim ") + version_string;
  chunk_.reserve(options_.chunk_size);
  record_.assign(mcap::kMagic.begin(), mcap::kMagic.end());
  mcap::append_header(record_, options_.profile, options_.library);
  emit(record_);
}

McapWriter::McapWriter(McapWriter&&) noexcept = default;
McapWriter::~McapWriter() = default;

void McapWriter::fail(std::string_view problem) const { throw input_error(name_, problem); }

void McapWriter::require_open(std::string_view operation) const {
  if (finished_) fail(std::string(operation) + " after the file was finished");
}

void McapWriter::emit(std::span<const unsigned char> bytes) {
  sink_->write(bytes);
  crc_ = mcap::crc32(crc_, bytes);
  offset_ += bytes.size();
}

std::uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding,
                                     std::string_view data) {
  require_open("a schema");
  if (schema_count_ == std::numeric_limits<std::uint16_t>::max()) fail("too many schemas");
  const auto id = static_cast<std::uint16_t>(schema_count_ + 1);
  mcap::append_schema(chunk_, id, name, encoding, data);
  mcap::append_schema(schemas_, id, name, encoding, data);
  schema_count_ = id;
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, std::string_view topic,
                                      std::string_view message_encoding,
                                      const McapMetadata& metadata) {
  require_open("a channel");
  if (schema_id > schema_count_) {
    fail("channel " + std::string(topic) + ": no schema " + std::to_string(schema_id));
  }
  if (channel_states_.size() == std::numeric_limits<std::uint16_t>::max()) {
    fail("too many channels");
  }
  const auto id = static_cast<std::uint16_t>(channel_states_.size() + 1);
  mcap::append_channel(chunk_, id, schema_id, topic, message_encoding, metadata);
  mcap::append_channel(channels_, id, schema_id, topic, message_encoding, metadata);
  channel_states_.emplace_back();
  return id;
}

void McapWriter::write_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                               std::uint64_t publish_time_ns, std::span<const unsigned char> data) {
  require_open("a message");
  if (channel_id == 0 || channel_id > channel_states_.size()) {
    fail("a message on channel " + std::to_string(channel_id) + ", which was never added");
  }
  ChannelState& channel = channel_states_[channel_id - 1];
  channel.chunk_index.emplace_back(log_time_ns, chunk_.size());
  // The sequence counts modulo 2^32, as the field's width allows.
  mcap::append_message(chunk_, channel_id, static_cast<std::uint32_t>(channel.message_count),
                       log_time_ns, publish_time_ns, data);
  ++channel.message_count;
  ++message_count_;
  if (!chunk_has_messages_) {
    chunk_start_time_ = chunk_end_time_ = log_time_ns;
    chunk_has_messages_ = true;
  }
  chunk_start_time_ = std::min(chunk_start_time_, log_time_ns);
  chunk_end_time_ = std::max(chunk_end_time_, log_time_ns);
  if (message_count_ == 1) start_time_ = end_time_ = log_time_ns;
  start_time_ = std::min(start_time_, log_time_ns);
  end_time_ = std::max(end_time_, log_time_ns);
  if (chunk_.size() >= options_.chunk_size) close_chunk();
}

void McapWriter::close_chunk() {
  if (chunk_.empty()) return;
  const std::uint32_t records_crc = mcap::crc32(0, chunk_);
  const std::span<const unsigned char> stored =
      compressor_ ? compressor_->compress(chunk_) : std::span<const unsigned char>(chunk_);
  const std::string_view compression = compressor_ ? "zstd" : "";
  mcap::ChunkIndexFields index;
  index.message_start_time = chunk_start_time_;
  index.message_end_time = chunk_end_time_;
  index.chunk_start_offset = offset_;
  index.compression = compression;
  index.compressed_size = stored.size();
  index.uncompressed_size = chunk_.size();

  record_.clear();
  mcap::append_chunk_prefix(record_, {chunk_start_time_, chunk_end_time_, chunk_.size(),
                                      records_crc, compression, stored.size()});
  emit(record_);
  emit(stored);
  index.chunk_length = offset_ - index.chunk_start_offset;

  const std::uint64_t indexes_start = offset_;
  for (std::size_t i = 0; i < channel_states_.size(); ++i) {
    auto& entries = channel_states_[i].chunk_index;
    if (entries.empty()) continue;
    const auto channel_id = static_cast<std::uint16_t>(i + 1);
    index.message_index_offsets.emplace_back(channel_id, offset_);
    record_.clear();
    mcap::append_message_index(record_, channel_id, entries);
    emit(record_);
    entries.clear();
  }
  index.message_index_length = offset_ - indexes_start;
  mcap::append_chunk_index(chunk_indexes_, index);

  ++chunk_count_;
  chunk_.clear();
  chunk_has_messages_ = false;
  chunk_start_time_ = chunk_end_time_ = 0;
}

void McapWriter::finish() {
  require_open("finishing");
  close_chunk();
  record_.clear();
  mcap::append_data_end(record_, crc_);
  emit(record_);

  const std::uint64_t summary_start = offset_;
  crc_ = 0;  // from here: the summary CRC
  struct Group {
    mcap::Opcode opcode;
    std::uint64_t start;
    std::uint64_t length;
  };
  std::vector<Group> groups;
  const auto emit_group = [&](mcap::Opcode opcode, std::span<const unsigned char> records) {
    if (records.empty()) return;
    groups.push_back({opcode, offset_, records.size()});
    emit(records);
  };
  emit_group(mcap::Opcode::schema, schemas_);
  emit_group(mcap::Opcode::channel, channels_);
  mcap::StatisticsFields statistics;
  statistics.message_count = message_count_;
  statistics.schema_count = schema_count_;
  statistics.channel_count = static_cast<std::uint32_t>(channel_states_.size());
  statistics.chunk_count = chunk_count_;
  statistics.message_start_time = start_time_;
  statistics.message_end_time = end_time_;
  for (std::size_t i = 0; i < channel_states_.size(); ++i) {
    statistics.channel_message_counts.emplace_back(static_cast<std::uint16_t>(i + 1),
                                                   channel_states_[i].message_count);
  }
  record_.clear();
  mcap::append_statistics(record_, statistics);
  emit_group(mcap::Opcode::statistics, record_);
  emit_group(mcap::Opcode::chunk_index, chunk_indexes_);

  const std::uint64_t summary_offset_start = offset_;
  record_.clear();
  for (const Group& group : groups) {
    mcap::append_summary_offset(record_, group.opcode, group.start, group.length);
  }
  mcap::append_footer_fields(record_, summary_start, summary_offset_start);
  emit(record_);
  record_.clear();
  mcap::append_footer_crc(record_, crc_);
  record_.insert(record_.end(), mcap::kMagic.begin(), mcap::kMagic.end());
  emit(record_);
  finished_ = true;
  sink_->finish();
}

std::size_t McapWriter::chunk_buffer_bytes() const {
  std::size_t bytes = chunk_.capacity() + record_.capacity();
  if (compressor_) bytes += compressor_->capacity();
  for (const ChannelState& channel : channel_states_) {
    bytes += channel.chunk_index.capacity() * sizeof(channel.chunk_index[0]);
  }
  return bytes;
}

std::size_t McapWriter::summary_buffer_bytes() const {
  return schemas_.capacity() + channels_.capacity() + chunk_indexes_.capacity();
}

}  // namespace owsim
