#include "lookout/io/mcap_writer.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "lookout/io/mcap_compression.h"
#include "lookout/io/mcap_format.h"

namespace lookout::io {
namespace {

using mcap::Opcode;

// Little-endian serialization, spec section "Serialization".
template <typename T>
void PutLittleEndian(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<std::uint8_t>(value >> (8 * i))));
  }
}
void PutU8(std::string& out, std::uint8_t value) { PutLittleEndian(out, value); }
void PutU16(std::string& out, std::uint16_t value) { PutLittleEndian(out, value); }
void PutU32(std::string& out, std::uint32_t value) { PutLittleEndian(out, value); }
void PutU64(std::string& out, std::uint64_t value) { PutLittleEndian(out, value); }

std::uint32_t CheckedU32Length(std::size_t size, std::string_view what) {
  if (size > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error(
        fmt::format("McapWriter: {} is {} bytes, MCAP allows at most 4 GiB", what, size));
  }
  return static_cast<std::uint32_t>(size);
}

// String and uint32-length-prefixed Bytes are serialized alike.
void PutString(std::string& out, std::string_view s, std::string_view what) {
  PutU32(out, CheckedU32Length(s.size(), what));
  out.append(s);
}

void PutRecordPrefix(std::string& out, Opcode opcode, std::uint64_t content_length) {
  PutU8(out, static_cast<std::uint8_t>(opcode));
  PutU64(out, content_length);
}

void PutRecord(std::string& out, Opcode opcode, std::string_view content) {
  PutRecordPrefix(out, opcode, content.size());
  out.append(content);
}

std::uint64_t CheckedTime(TimeNs t, std::string_view what) {
  if (t < 0) {
    throw std::invalid_argument(
        fmt::format("McapWriter: {} is {} ns; MCAP timestamps cannot be negative", what, t));
  }
  return static_cast<std::uint64_t>(t);
}

}  // namespace

class McapWriter::Impl {
  // Nested rather than in the anonymous namespace: the members of a class the header declares
  // should not have types of internal linkage (GCC's -Wsubobject-linkage, in a unity build).
  struct MessageIndexEntry {
    std::uint64_t log_time = 0;
    std::uint64_t offset = 0;  // from the start of the chunk's uncompressed records
  };

  struct ChunkIndex {
    std::uint64_t message_start_time = 0;
    std::uint64_t message_end_time = 0;
    std::uint64_t chunk_start_offset = 0;
    std::uint64_t chunk_length = 0;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length = 0;
    std::uint64_t compressed_size = 0;
    std::uint64_t uncompressed_size = 0;
  };

  // Earliest and latest log time of a set of messages; MCAP writes 0 and 0 for no messages.
  struct TimeRange {
    std::uint64_t start = std::numeric_limits<std::uint64_t>::max();
    std::uint64_t end = 0;
    void Add(std::uint64_t t) {
      start = std::min(start, t);
      end = std::max(end, t);
    }
    std::uint64_t start_or_zero() const { return start <= end ? start : 0; }
  };

 public:
  Impl(std::string path, McapWriterOptions options)
      : path_(std::move(path)), part_path_(path_ + ".part"), options_(std::move(options)) {
    out_.open(part_path_, std::ios::binary | std::ios::trunc);
    if (!out_) {
      throw std::runtime_error(
          fmt::format("cannot open {} for writing: {}", part_path_, std::strerror(errno)));
    }
    std::string start(mcap::kMagic);
    std::string header;
    PutString(header, options_.profile, "profile");
    PutString(header, options_.library, "library");
    PutRecord(start, Opcode::kHeader, header);
    WriteBytes(start);
  }

  ~Impl() {
    if (finished_) return;
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(part_path_, ignored);
  }

  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  std::uint16_t AddSchema(std::string_view name, std::string_view encoding, std::string_view data) {
    CheckOpen();
    const std::uint16_t id = NextId(schema_records_, "schemas");
    std::string content;
    PutU16(content, id);
    PutString(content, name, "schema name");
    PutString(content, encoding, "schema encoding");
    PutString(content, data, "schema data");
    AddDefinition(schema_records_, id, Opcode::kSchema, content);
    return id;
  }

  std::uint16_t AddChannel(std::uint16_t schema_id, std::string_view topic,
                           std::string_view message_encoding,
                           const std::unordered_map<std::string, std::string>& metadata) {
    CheckOpen();
    if (schema_id != 0 && schema_records_.count(schema_id) == 0) {
      throw std::invalid_argument(
          fmt::format("McapWriter: channel '{}' refers to unknown schema {}", topic, schema_id));
    }
    const std::uint16_t id = NextId(channel_records_, "channels");
    std::string content;
    PutU16(content, id);
    PutU16(content, schema_id);
    PutString(content, topic, "topic");
    PutString(content, message_encoding, "message encoding");
    // Sorted keys, so that the bytes do not depend on the hash map's iteration order.
    const std::map<std::string, std::string> sorted(metadata.begin(), metadata.end());
    std::string entries;
    for (const auto& [key, value] : sorted) {
      PutString(entries, key, "metadata key");
      PutString(entries, value, "metadata value");
    }
    PutString(content, entries, "channel metadata");
    AddDefinition(channel_records_, id, Opcode::kChannel, content);
    next_sequence_[id] = 0;
    return id;
  }

  void Write(std::uint16_t channel_id, TimeNs log_time, TimeNs publish_time,
             std::string_view data) {
    CheckOpen();
    const auto sequence = next_sequence_.find(channel_id);
    if (sequence == next_sequence_.end()) {
      throw std::invalid_argument(
          fmt::format("McapWriter: message on unknown channel {}", channel_id));
    }
    const std::uint64_t log = CheckedTime(log_time, "log_time");
    const std::uint64_t publish = CheckedTime(publish_time, "publish_time");

    const std::uint64_t offset = chunk_records_.size();
    PutRecordPrefix(chunk_records_, Opcode::kMessage, 2 + 4 + 8 + 8 + data.size());
    PutU16(chunk_records_, channel_id);
    // The API has no publisher sequence numbers, so the recorder numbers each channel's
    // messages 0, 1, 2, ... in the order they are written.
    PutU32(chunk_records_, sequence->second++);
    PutU64(chunk_records_, log);
    PutU64(chunk_records_, publish);
    chunk_records_.append(data);

    chunk_message_index_[channel_id].push_back({log, offset});
    chunk_times_.Add(log);
    file_times_.Add(log);
    ++message_count_;
    ++channel_message_counts_[channel_id];
    if (chunk_records_.size() >= options_.chunk_size_bytes) FlushChunk();
  }

  void Finish() {
    CheckOpen();
    FlushChunk();

    std::string data_end;
    PutU32(data_end, data_section_crc_);
    data_section_done_ = true;
    std::string record;
    PutRecord(record, Opcode::kDataEnd, data_end);
    WriteBytes(record);

    WriteSummaryAndFooter();
    out_.close();
    if (!out_) {
      throw std::runtime_error(
          fmt::format("cannot write {}: {}", part_path_, std::strerror(errno)));
    }
    std::error_code error;
    std::filesystem::rename(part_path_, path_, error);
    if (error) {
      throw std::runtime_error(
          fmt::format("cannot rename {} to {}: {}", part_path_, path_, error.message()));
    }
    finished_ = true;
  }

 private:
  void CheckOpen() const {
    if (finished_) throw std::logic_error("McapWriter: used after Finish()");
  }

  static std::uint16_t NextId(const std::map<std::uint16_t, std::string>& records,
                              std::string_view what) {
    // Ids start at 1: schema id 0 means "no schema", and channels follow suit.
    if (records.size() >= std::numeric_limits<std::uint16_t>::max()) {
      throw std::length_error(fmt::format("McapWriter: more than 65535 {}", what));
    }
    return static_cast<std::uint16_t>(records.size() + 1);
  }

  // Schema and Channel records go into the open chunk, as the reference writers do, so a reader
  // streaming the data section meets each before the first message that needs it; copies go
  // into the summary so an indexed reader finds them without scanning.
  void AddDefinition(std::map<std::uint16_t, std::string>& records, std::uint16_t id, Opcode opcode,
                     std::string_view content) {
    std::string record;
    PutRecord(record, opcode, content);
    chunk_records_.append(record);
    records.emplace(id, std::move(record));
  }

  // Writes the open chunk, compressed, and one MessageIndex record per channel in it.
  void FlushChunk() {
    if (chunk_records_.empty()) return;
    const std::string compressed = mcap::CompressChunkRecords(options_.compression, chunk_records_);
    const std::string_view compression = mcap::CompressionName(options_.compression);

    ChunkIndex index;
    index.message_start_time = chunk_times_.start_or_zero();
    index.message_end_time = chunk_times_.end;
    index.uncompressed_size = chunk_records_.size();
    index.compressed_size = compressed.size();

    std::string fields;
    PutU64(fields, index.message_start_time);
    PutU64(fields, index.message_end_time);
    PutU64(fields, index.uncompressed_size);
    PutU32(fields, mcap::Crc32(chunk_records_));
    PutString(fields, compression, "compression");
    PutU64(fields, index.compressed_size);
    std::string prefix;
    PutRecordPrefix(prefix, Opcode::kChunk, fields.size() + compressed.size());
    index.chunk_start_offset = offset_;
    WriteBytes(prefix);
    WriteBytes(fields);
    WriteBytes(compressed);
    index.chunk_length = offset_ - index.chunk_start_offset;

    const std::uint64_t message_index_start = offset_;
    for (auto& [channel_id, entries] : chunk_message_index_) {
      // The spec wants index entries in log-time order; stable, so equal times keep file order.
      std::stable_sort(entries.begin(), entries.end(),
                       [](const MessageIndexEntry& a, const MessageIndexEntry& b) {
                         return a.log_time < b.log_time;
                       });
      std::string content;
      PutU16(content, channel_id);
      PutU32(content, CheckedU32Length(16 * entries.size(), "message index"));
      for (const MessageIndexEntry& e : entries) {
        PutU64(content, e.log_time);
        PutU64(content, e.offset);
      }
      std::string record;
      PutRecord(record, Opcode::kMessageIndex, content);
      index.message_index_offsets[channel_id] = offset_;
      WriteBytes(record);
    }
    index.message_index_length = offset_ - message_index_start;

    chunk_indexes_.push_back(std::move(index));
    chunk_records_.clear();
    chunk_message_index_.clear();
    chunk_times_ = {};
  }

  // Summary section (Schema, Channel, Statistics, ChunkIndex groups), Summary Offset section,
  // Footer and closing magic, built in memory so the footer's CRC covers exactly what is written.
  void WriteSummaryAndFooter() {
    const std::uint64_t summary_start = offset_;
    std::string summary;
    std::vector<std::pair<Opcode, std::pair<std::uint64_t, std::uint64_t>>> groups;
    const auto add_group = [&](Opcode opcode, auto&& append_records) {
      const std::size_t begin = summary.size();
      append_records();
      if (summary.size() > begin) {
        groups.push_back({opcode, {summary_start + begin, summary.size() - begin}});
      }
    };
    add_group(Opcode::kSchema, [&] {
      for (const auto& [id, record] : schema_records_) summary.append(record);
    });
    add_group(Opcode::kChannel, [&] {
      for (const auto& [id, record] : channel_records_) summary.append(record);
    });
    add_group(Opcode::kStatistics, [&] { PutRecord(summary, Opcode::kStatistics, Statistics()); });
    add_group(Opcode::kChunkIndex, [&] {
      for (const ChunkIndex& index : chunk_indexes_) {
        PutRecord(summary, Opcode::kChunkIndex, ChunkIndexContent(index));
      }
    });

    const std::uint64_t summary_offset_start = summary_start + summary.size();
    for (const auto& [opcode, range] : groups) {
      std::string content;
      PutU8(content, static_cast<std::uint8_t>(opcode));
      PutU64(content, range.first);
      PutU64(content, range.second);
      PutRecord(summary, Opcode::kSummaryOffset, content);
    }

    // summary_crc covers the summary and summary offset sections and the footer up to and
    // including summary_offset_start.
    PutRecordPrefix(summary, Opcode::kFooter, mcap::kFooterContentBytes);
    PutU64(summary, summary_start);
    PutU64(summary, summary_offset_start);
    PutU32(summary, mcap::Crc32(summary));
    summary.append(mcap::kMagic);
    WriteBytes(summary);
  }

  std::string Statistics() const {
    std::string content;
    PutU64(content, message_count_);
    PutU16(content, static_cast<std::uint16_t>(schema_records_.size()));
    PutU32(content, static_cast<std::uint32_t>(channel_records_.size()));
    PutU32(content, 0);  // attachment_count: Lookout writes none
    PutU32(content, 0);  // metadata_count: Lookout writes none
    PutU32(content, CheckedU32Length(chunk_indexes_.size(), "chunk count"));
    PutU64(content, file_times_.start_or_zero());
    PutU64(content, file_times_.end);
    PutU32(content, CheckedU32Length(10 * channel_message_counts_.size(), "message counts"));
    for (const auto& [channel_id, count] : channel_message_counts_) {
      PutU16(content, channel_id);
      PutU64(content, count);
    }
    return content;
  }

  std::string ChunkIndexContent(const ChunkIndex& index) const {
    std::string content;
    PutU64(content, index.message_start_time);
    PutU64(content, index.message_end_time);
    PutU64(content, index.chunk_start_offset);
    PutU64(content, index.chunk_length);
    PutU32(content, CheckedU32Length(10 * index.message_index_offsets.size(), "offsets"));
    for (const auto& [channel_id, offset] : index.message_index_offsets) {
      PutU16(content, channel_id);
      PutU64(content, offset);
    }
    PutU64(content, index.message_index_length);
    // Every chunk of a file uses the writer's one compression.
    PutString(content, mcap::CompressionName(options_.compression), "compression");
    PutU64(content, index.compressed_size);
    PutU64(content, index.uncompressed_size);
    return content;
  }

  void WriteBytes(std::string_view bytes) {
    out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out_) {
      throw std::runtime_error(
          fmt::format("cannot write {}: {}", part_path_, std::strerror(errno)));
    }
    if (!data_section_done_) data_section_crc_ = mcap::Crc32(bytes, data_section_crc_);
    offset_ += bytes.size();
  }

  std::string path_;
  std::string part_path_;
  McapWriterOptions options_;
  std::ofstream out_;
  std::uint64_t offset_ = 0;  // bytes written so far, i.e. the file offset of the next byte
  // CRC of every byte before DataEnd (spec: from the start of the file, magic included).
  std::uint32_t data_section_crc_ = 0;
  bool data_section_done_ = false;
  bool finished_ = false;

  std::map<std::uint16_t, std::string> schema_records_;   // id -> whole record
  std::map<std::uint16_t, std::string> channel_records_;  // id -> whole record
  std::map<std::uint16_t, std::uint32_t> next_sequence_;  // channel id -> next Message.sequence

  std::string chunk_records_;  // the open chunk, uncompressed
  std::map<std::uint16_t, std::vector<MessageIndexEntry>> chunk_message_index_;
  TimeRange chunk_times_;

  std::vector<ChunkIndex> chunk_indexes_;
  std::uint64_t message_count_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts_;
  TimeRange file_times_;
};

McapWriter::McapWriter(std::string path, McapWriterOptions options)
    : impl_(std::make_unique<Impl>(std::move(path), std::move(options))) {}

McapWriter::~McapWriter() = default;

std::uint16_t McapWriter::AddSchema(std::string_view name, std::string_view encoding,
                                    std::string_view data) {
  return impl_->AddSchema(name, encoding, data);
}

std::uint16_t McapWriter::AddChannel(std::uint16_t schema_id, std::string_view topic,
                                     std::string_view message_encoding,
                                     const std::unordered_map<std::string, std::string>& metadata) {
  return impl_->AddChannel(schema_id, topic, message_encoding, metadata);
}

void McapWriter::Write(std::uint16_t channel_id, TimeNs log_time, TimeNs publish_time,
                       std::string_view data) {
  impl_->Write(channel_id, log_time, publish_time, data);
}

void McapWriter::Finish() { impl_->Finish(); }

}  // namespace lookout::io
