#include "io/mcap/mcap_writer.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "geometry/error.hpp"
#include "owsim/version.hpp"

namespace owsim {

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
      options_(options),
      chunk_(options.compression, options.zstd_level) {
  if (options_.chunk_size == 0) fail("the chunk size must be positive");
  if (options_.library.empty()) options_.library = std::string("owsim ") + version_string;
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
  chunk_.add_schema(id, name, encoding, data);
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
  if (channel_messages_.size() == std::numeric_limits<std::uint16_t>::max()) {
    fail("too many channels");
  }
  const auto id = static_cast<std::uint16_t>(channel_messages_.size() + 1);
  chunk_.add_channel(id, schema_id, topic, message_encoding, metadata);
  mcap::append_channel(channels_, id, schema_id, topic, message_encoding, metadata);
  channel_messages_.push_back(0);
  return id;
}

void McapWriter::write_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                               std::uint64_t publish_time_ns, std::span<const unsigned char> data) {
  require_open("a message");
  if (channel_id == 0 || channel_id > channel_messages_.size()) {
    fail("a message on channel " + std::to_string(channel_id) + ", which was never added");
  }
  // The sequence counts modulo 2^32, as the field's width allows.
  std::uint64_t& count = channel_messages_[channel_id - 1];
  chunk_.add_message(channel_id, static_cast<std::uint32_t>(count), log_time_ns, publish_time_ns,
                     data);
  ++count;
  if (message_count_ == 0) start_time_ = end_time_ = log_time_ns;
  start_time_ = std::min(start_time_, log_time_ns);
  end_time_ = std::max(end_time_, log_time_ns);
  ++message_count_;
  if (chunk_.records_size() >= options_.chunk_size) close_chunk();
}

void McapWriter::close_chunk() {
  require_open("a chunk");
  if (chunk_.empty()) return;
  chunk_.finish();
  place(chunk_);
  chunk_.clear();
}

void McapWriter::write_chunk(const McapChunk& chunk) {
  require_open("a chunk");
  if (!chunk.finished()) fail("a chunk that was not finished");
  for (const McapChunk::ChannelMessages& channel : chunk.channels()) {
    if (channel.channel_id > channel_messages_.size()) {
      fail("a chunk with messages on channel " + std::to_string(channel.channel_id) +
           ", which was never added");
    }
    const auto expected = static_cast<std::uint32_t>(channel_messages_[channel.channel_id - 1]);
    if (channel.first_sequence != expected) {
      fail("a chunk whose messages on channel " + std::to_string(channel.channel_id) +
           " start at sequence " + std::to_string(channel.first_sequence) + ", not " +
           std::to_string(expected));
    }
  }
  close_chunk();
  for (const McapChunk::ChannelMessages& channel : chunk.channels()) {
    channel_messages_[channel.channel_id - 1] += channel.count;
  }
  if (chunk.has_messages()) {
    if (message_count_ == 0) start_time_ = end_time_ = chunk.start_time();
    start_time_ = std::min(start_time_, chunk.start_time());
    end_time_ = std::max(end_time_, chunk.end_time());
    message_count_ += chunk.message_count();
  }
  place(chunk);
}

void McapWriter::place(const McapChunk& chunk) {
  const std::span<const unsigned char> bytes = chunk.bytes();
  mcap::ChunkIndexFields index;
  index.message_start_time = chunk.start_time();
  index.message_end_time = chunk.end_time();
  index.chunk_start_offset = offset_;
  index.chunk_length = chunk.chunk_record_size();
  for (const auto& [channel_id, at] : chunk.message_index_offsets()) {
    index.message_index_offsets.emplace_back(channel_id, offset_ + at);
  }
  index.message_index_length = bytes.size() - chunk.chunk_record_size();
  index.compression = chunk.compression();
  index.compressed_size = chunk.compressed_size();
  index.uncompressed_size = chunk.records_size();
  mcap::append_chunk_index(chunk_indexes_, index);
  sink_->write(bytes);
  crc_ = mcap::crc32_combine(crc_, chunk.crc(), bytes.size());
  offset_ += bytes.size();
  ++chunk_count_;
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
  statistics.channel_count = static_cast<std::uint32_t>(channel_messages_.size());
  statistics.chunk_count = chunk_count_;
  statistics.message_start_time = start_time_;
  statistics.message_end_time = end_time_;
  for (std::size_t i = 0; i < channel_messages_.size(); ++i) {
    statistics.channel_message_counts.emplace_back(static_cast<std::uint16_t>(i + 1),
                                                   channel_messages_[i]);
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
  return chunk_.buffer_bytes() + record_.capacity();
}

std::size_t McapWriter::summary_buffer_bytes() const {
  return schemas_.capacity() + channels_.capacity() + chunk_indexes_.capacity();
}

}  // namespace owsim
