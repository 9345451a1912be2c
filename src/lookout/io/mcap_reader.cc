#include "lookout/io/mcap_reader.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "lookout/core/input_error.h"
#include "lookout/io/mcap_compression.h"
#include "lookout/io/mcap_format.h"

namespace lookout::io {
namespace {

using mcap::Opcode;

std::string_view OpcodeName(std::uint8_t opcode) {
  static constexpr std::array<std::string_view, 16> kNames = {
      "opcode 0x00", "Header",        "Footer",          "Schema",
      "Channel",     "Message",       "Chunk",           "MessageIndex",
      "ChunkIndex",  "Attachment",    "AttachmentIndex", "Statistics",
      "Metadata",    "MetadataIndex", "SummaryOffset",   "DataEnd"};
  return opcode < kNames.size() ? kNames[opcode] : "unknown";
}

// A string from the file, made safe to print in an error message.
std::string Printable(std::string_view s) {
  constexpr std::size_t kMaxChars = 40;
  std::string out;
  for (const char c : s.substr(0, kMaxChars)) out.push_back(c >= 0x20 && c < 0x7f ? c : '?');
  if (s.size() > kMaxChars) out += "...";
  return out;
}

// Where a record is, for error messages: a file offset, or an offset inside the uncompressed
// records of the chunk at `chunk_offset`.
struct Where {
  std::uint64_t offset = 0;
  std::uint8_t opcode = 0;
  std::optional<std::uint64_t> chunk_offset;

  std::string Describe() const {
    const std::string record = opcode <= static_cast<std::uint8_t>(Opcode::kDataEnd)
                                   ? fmt::format("{} record", OpcodeName(opcode))
                                   : fmt::format("record with opcode 0x{:02x}", opcode);
    if (chunk_offset) {
      return fmt::format("{} at offset {} in the chunk at byte {}", record, offset, *chunk_offset);
    }
    return fmt::format("{} at byte {}", record, offset);
  }
};

[[noreturn]] void Fail(const std::string& source, const std::string& problem) {
  throw InputError(source, 0, "", problem);
}

// Reads the little-endian fields of one record's content and refuses to read past its end.
class FieldReader {
 public:
  FieldReader(std::string_view content, const Where& where, const std::string& source)
      : rest_(content), where_(where), source_(source) {}

  std::uint8_t U8(std::string_view field) { return Fixed<std::uint8_t>(field); }
  std::uint16_t U16(std::string_view field) { return Fixed<std::uint16_t>(field); }
  std::uint32_t U32(std::string_view field) { return Fixed<std::uint32_t>(field); }
  std::uint64_t U64(std::string_view field) { return Fixed<std::uint64_t>(field); }

  TimeNs Time(std::string_view field) {
    const std::uint64_t t = U64(field);
    if (t > static_cast<std::uint64_t>(std::numeric_limits<TimeNs>::max())) {
      Fail(source_, fmt::format("{}: {} {} ns is beyond the signed 64-bit range Lookout uses",
                                where_.Describe(), field, t));
    }
    return static_cast<TimeNs>(t);
  }

  std::string_view Bytes(std::uint64_t n, std::string_view field) {
    if (n > rest_.size()) {
      Fail(source_, fmt::format("truncated: {} needs {} bytes for {}, {} remain", where_.Describe(),
                                n, field, rest_.size()));
    }
    const std::string_view out = rest_.substr(0, static_cast<std::size_t>(n));
    rest_.remove_prefix(static_cast<std::size_t>(n));
    return out;
  }

  // String, uint32-length-prefixed Bytes, and the byte-length prefix of Array and Map.
  std::string_view Prefixed(std::string_view field) { return Bytes(U32(field), field); }

  std::string_view Rest() { return Bytes(rest_.size(), "rest"); }
  bool empty() const { return rest_.empty(); }
  const Where& where() const { return where_; }

 private:
  template <typename T>
  T Fixed(std::string_view field) {
    const std::string_view bytes = Bytes(sizeof(T), field);
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      value |= std::uint64_t{static_cast<std::uint8_t>(bytes[i])} << (8 * i);
    }
    return static_cast<T>(value);
  }

  std::string_view rest_;
  Where where_;
  const std::string& source_;
};

struct Record {
  Where where;
  std::string_view content;
  std::uint64_t end = 0;  // offset just past the record, same frame as where.offset
  Opcode opcode() const { return static_cast<Opcode>(where.opcode); }
};

// Splits bytes into <opcode><uint64 length><content> records. `base` is the offset of the first
// byte, in the file or in a chunk's records.
class RecordScanner {
 public:
  RecordScanner(std::string_view bytes, std::uint64_t base,
                std::optional<std::uint64_t> chunk_offset, const std::string& source)
      : bytes_(bytes), base_(base), chunk_offset_(chunk_offset), source_(source) {}

  bool done() const { return position_ == bytes_.size(); }
  std::uint64_t offset() const { return base_ + position_; }

  Record Next() {
    const std::size_t remaining = bytes_.size() - position_;
    Where where{offset(), 0, chunk_offset_};
    if (remaining < mcap::kRecordPrefixBytes) {
      where.opcode = static_cast<std::uint8_t>(bytes_[position_]);
      Fail(source_, fmt::format("truncated: {} needs a 9-byte opcode and length, {} bytes remain",
                                where.Describe(), remaining));
    }
    FieldReader prefix(bytes_.substr(position_, mcap::kRecordPrefixBytes), where, source_);
    where.opcode = prefix.U8("opcode");
    const std::uint64_t length = prefix.U64("record length");
    const std::size_t available = remaining - mcap::kRecordPrefixBytes;
    if (where.opcode == 0)
      Fail(source_, fmt::format("{}: 0x00 is not a valid opcode", where.Describe()));
    if (length > available) {
      Fail(source_, fmt::format("truncated: {} claims {} bytes, {} remain", where.Describe(),
                                length, available));
    }
    Record record;
    record.where = where;
    record.content =
        bytes_.substr(position_ + mcap::kRecordPrefixBytes, static_cast<std::size_t>(length));
    position_ += mcap::kRecordPrefixBytes + static_cast<std::size_t>(length);
    record.end = offset();
    return record;
  }

 private:
  std::string_view bytes_;
  std::uint64_t base_;
  std::optional<std::uint64_t> chunk_offset_;
  const std::string& source_;
  std::size_t position_ = 0;
};

// What the data section held, kept to check the summary's indexes against it.
struct ChunkFacts {
  std::uint64_t length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
};

struct ChunkMessage {
  std::uint64_t offset = 0;  // in the chunk's uncompressed records
  std::uint16_t channel_id = 0;
  TimeNs log_time = 0;
};

// One pass over the file: data section, summary section, summary offsets, footer.
class Parser {
 public:
  Parser(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  McapContents Parse() {
    if (bytes_.substr(0, mcap::kMagic.size()) != mcap::kMagic) {
      Fail(source_, "not an MCAP file: it does not start with the MCAP magic");
    }
    RecordScanner scanner(bytes_.substr(mcap::kMagic.size()), mcap::kMagic.size(), std::nullopt,
                          source_);
    ReadHeader(scanner);
    while (phase_ != Phase::kDone) {
      if (scanner.done()) {
        Fail(source_, fmt::format("truncated: file ends at byte {} before the Footer record",
                                  scanner.offset()));
      }
      const Record record = scanner.Next();
      switch (phase_) {
        case Phase::kData:
          ReadDataRecord(record);
          break;
        case Phase::kSummary:
        case Phase::kSummaryOffsets:
          ReadSummaryRecord(record);
          break;
        case Phase::kDone:
          break;
      }
    }
    const std::uint64_t tail = bytes_.size() - scanner.offset();
    if (tail != mcap::kMagic.size() || bytes_.substr(bytes_.size() - tail) != mcap::kMagic) {
      Fail(source_, fmt::format("truncated or corrupt: {} bytes follow the Footer, expected the "
                                "8-byte closing MCAP magic",
                                tail));
    }
    return std::move(contents_);
  }

 private:
  enum class Phase { kData, kSummary, kSummaryOffsets, kDone };

  [[noreturn]] void FailAt(const Where& where, const std::string& problem) const {
    Fail(source_, fmt::format("{}: {}", where.Describe(), problem));
  }

  void ReadHeader(RecordScanner& scanner) {
    if (scanner.done()) Fail(source_, "truncated: the file ends after the magic, no Header");
    const Record record = scanner.Next();
    if (record.opcode() != Opcode::kHeader) {
      FailAt(record.where, "the first record must be the Header");
    }
    FieldReader fields(record.content, record.where, source_);
    contents_.profile = fields.Prefixed("profile");
    contents_.library = fields.Prefixed("library");
  }

  void ReadDataRecord(const Record& record) {
    const bool after_chunk = message_index_may_follow_;
    message_index_may_follow_ = false;
    switch (record.opcode()) {
      case Opcode::kSchema:
      case Opcode::kChannel:
      case Opcode::kMessage:
        ReadChunkableRecord(record);
        return;
      case Opcode::kChunk:
        ReadChunk(record);
        message_index_may_follow_ = true;
        return;
      case Opcode::kMessageIndex:
        if (!after_chunk)
          FailAt(record.where, "does not follow a Chunk and its MessageIndex records");
        ReadMessageIndex(record);
        message_index_may_follow_ = true;
        return;
      case Opcode::kAttachment:
      case Opcode::kMetadata:
        return;
      case Opcode::kDataEnd:
        ReadDataEnd(record);
        return;
      case Opcode::kFooter:
        FailAt(record.where, "comes before the DataEnd record that must end the data section");
      case Opcode::kHeader:
      case Opcode::kChunkIndex:
      case Opcode::kAttachmentIndex:
      case Opcode::kStatistics:
      case Opcode::kMetadataIndex:
      case Opcode::kSummaryOffset:
        FailAt(record.where, "is not allowed in the data section");
    }
    // Opcodes this reader does not know are skipped, as the spec asks.
  }

  // Schema, Channel and Message records, in a chunk or directly in the data section.
  void ReadChunkableRecord(const Record& record) {
    FieldReader fields(record.content, record.where, source_);
    switch (record.opcode()) {
      case Opcode::kSchema:
        AddSchema(fields);
        return;
      case Opcode::kChannel:
        AddChannel(fields);
        return;
      case Opcode::kMessage:
        AddMessage(fields);
        return;
      default:
        return;
    }
  }

  void AddSchema(FieldReader& fields) {
    McapSchema schema;
    schema.id = fields.U16("id");
    schema.name = fields.Prefixed("name");
    schema.encoding = fields.Prefixed("encoding");
    schema.data = fields.Prefixed("data");
    if (schema.id == 0) return;  // spec: a Schema with id 0 is invalid and ignored
    AddOnce(contents_.schemas, schema.id, schema, fields, "schema");
  }

  void AddChannel(FieldReader& fields) {
    McapChannel channel;
    channel.id = fields.U16("id");
    channel.schema_id = fields.U16("schema_id");
    channel.topic = fields.Prefixed("topic");
    channel.message_encoding = fields.Prefixed("message_encoding");
    FieldReader metadata(fields.Prefixed("metadata"), fields.where(), source_);
    while (!metadata.empty()) {
      std::string key(metadata.Prefixed("metadata key"));
      channel.metadata.try_emplace(std::move(key), metadata.Prefixed("metadata value"));
    }
    if (channel.schema_id != 0 && contents_.schemas.count(channel.schema_id) == 0) {
      FailAt(fields.where(), fmt::format("channel '{}' refers to schema {}, not defined before it",
                                         Printable(channel.topic), channel.schema_id));
    }
    AddOnce(contents_.channels, channel.id, channel, fields, "channel");
  }

  // A schema or channel may come again (in chunks and in the summary, by the spec), the same;
  // never changed.
  template <typename Record>
  void AddOnce(std::map<std::uint16_t, Record>& records, std::uint16_t id, const Record& record,
               const FieldReader& fields, std::string_view kind) {
    const auto [it, inserted] = records.try_emplace(id, record);
    if (!inserted && !(it->second == record)) {
      FailAt(fields.where(), fmt::format("redefines {} {} differently", kind, id));
    }
  }

  void AddMessage(FieldReader& fields) {
    McapMessage message;
    message.channel_id = fields.U16("channel_id");
    message.sequence = fields.U32("sequence");
    message.log_time = fields.Time("log_time");
    message.publish_time = fields.Time("publish_time");
    message.data = fields.Rest();
    if (contents_.channels.count(message.channel_id) == 0) {
      FailAt(fields.where(),
             fmt::format("refers to channel {}, not defined before it", message.channel_id));
    }
    contents_.messages.push_back(std::move(message));
  }

  void ReadChunk(const Record& record) {
    FieldReader fields(record.content, record.where, source_);
    ChunkFacts facts;
    facts.length = record.end - record.where.offset;
    facts.message_start_time = fields.U64("message_start_time");
    facts.message_end_time = fields.U64("message_end_time");
    facts.uncompressed_size = fields.U64("uncompressed_size");
    const std::uint32_t crc = fields.U32("uncompressed_crc");
    facts.compression = fields.Prefixed("compression");
    const std::string_view compressed = fields.Bytes(fields.U64("records length"), "records");
    facts.compressed_size = compressed.size();
    if (facts.uncompressed_size > mcap::kMaxChunkUncompressedBytes) {
      FailAt(record.where, fmt::format("uncompressed_size {} is over the {} byte limit",
                                       facts.uncompressed_size, mcap::kMaxChunkUncompressedBytes));
    }
    const mcap::DecompressedChunk chunk =
        mcap::DecompressChunkRecords(facts.compression, compressed, facts.uncompressed_size);
    if (!chunk.ok()) {
      FailAt(record.where,
             fmt::format("compression '{}': {}", Printable(facts.compression), chunk.problem));
    }
    if (crc != 0 && mcap::Crc32(chunk.records) != crc) {
      FailAt(record.where, fmt::format("CRC mismatch: records have CRC 0x{:08x}, the chunk says "
                                       "0x{:08x} (corrupted)",
                                       mcap::Crc32(chunk.records), crc));
    }

    chunk_messages_.clear();
    RecordScanner scanner(chunk.records, 0, record.where.offset, source_);
    while (!scanner.done()) {
      const Record inner = scanner.Next();
      switch (inner.opcode()) {
        case Opcode::kSchema:
        case Opcode::kChannel:
          ReadChunkableRecord(inner);
          break;
        case Opcode::kMessage: {
          ReadChunkableRecord(inner);
          const McapMessage& message = contents_.messages.back();
          const auto log_time = static_cast<std::uint64_t>(message.log_time);
          if (log_time < facts.message_start_time || log_time > facts.message_end_time) {
            FailAt(inner.where,
                   fmt::format("log_time {} is outside the chunk's [{}, {}]", message.log_time,
                               facts.message_start_time, facts.message_end_time));
          }
          chunk_messages_.push_back({inner.where.offset, message.channel_id, message.log_time});
          break;
        }
        default:
          if (inner.where.opcode <= static_cast<std::uint8_t>(Opcode::kDataEnd)) {
            FailAt(inner.where, "is not allowed inside a chunk");
          }
          break;
      }
    }
    ++contents_.chunk_count;
    chunks_.emplace(record.where.offset, std::move(facts));
  }

  // Each entry must point at a message of its channel, with its log time, in the chunk just read.
  void ReadMessageIndex(const Record& record) {
    FieldReader fields(record.content, record.where, source_);
    const std::uint16_t channel_id = fields.U16("channel_id");
    FieldReader entries(fields.Prefixed("records"), record.where, source_);
    while (!entries.empty()) {
      const TimeNs log_time = entries.Time("log_time");
      const std::uint64_t offset = entries.U64("offset");
      const auto it =
          std::lower_bound(chunk_messages_.begin(), chunk_messages_.end(), offset,
                           [](const ChunkMessage& m, std::uint64_t o) { return m.offset < o; });
      if (it == chunk_messages_.end() || it->offset != offset || it->channel_id != channel_id ||
          it->log_time != log_time) {
        FailAt(record.where,
               fmt::format("entry (log_time {}, offset {}) is not a message of channel {} in the "
                           "chunk before it",
                           log_time, offset, channel_id));
      }
    }
    message_indexes_.emplace(record.where.offset, channel_id);
  }

  void ReadDataEnd(const Record& record) {
    FieldReader fields(record.content, record.where, source_);
    const std::uint32_t crc = fields.U32("data_section_crc");
    const std::string_view data_section =
        bytes_.substr(0, static_cast<std::size_t>(record.where.offset));
    if (crc != 0 && mcap::Crc32(data_section) != crc) {
      FailAt(record.where, fmt::format("data section CRC mismatch: bytes 0..{} have CRC 0x{:08x}, "
                                       "DataEnd says 0x{:08x} (corrupted)",
                                       record.where.offset, mcap::Crc32(data_section), crc));
    }
    summary_start_ = record.end;
    phase_ = Phase::kSummary;
  }

  void ReadSummaryRecord(const Record& record) {
    if (record.opcode() == Opcode::kFooter) {
      ReadFooter(record);
      return;
    }
    if (record.opcode() == Opcode::kSummaryOffset) {
      if (phase_ == Phase::kSummary) summary_offset_start_ = record.where.offset;
      phase_ = Phase::kSummaryOffsets;
      ReadSummaryOffset(record);
      return;
    }
    const bool unknown = record.where.opcode > static_cast<std::uint8_t>(Opcode::kDataEnd);
    if (phase_ == Phase::kSummaryOffsets && !unknown) {
      FailAt(record.where, "follows a SummaryOffset record; only SummaryOffset records may");
    }
    summary_records_.push_back({record.where.offset, record.end, record.where.opcode});
    FieldReader fields(record.content, record.where, source_);
    switch (record.opcode()) {
      case Opcode::kSchema:
        AddSchema(fields);
        return;
      case Opcode::kChannel:
        AddChannel(fields);
        return;
      case Opcode::kStatistics:
        ReadStatistics(fields);
        return;
      case Opcode::kChunkIndex:
        ReadChunkIndex(fields);
        return;
      case Opcode::kAttachmentIndex:
      case Opcode::kMetadataIndex:
        return;
      default:
        if (!unknown) FailAt(record.where, "is not allowed in the summary section");
        return;
    }
  }

  void ReadStatistics(FieldReader& fields) {
    McapStatistics stats;
    stats.message_count = fields.U64("message_count");
    stats.schema_count = fields.U16("schema_count");
    stats.channel_count = fields.U32("channel_count");
    stats.attachment_count = fields.U32("attachment_count");
    stats.metadata_count = fields.U32("metadata_count");
    stats.chunk_count = fields.U32("chunk_count");
    stats.message_start_time = fields.Time("message_start_time");
    stats.message_end_time = fields.Time("message_end_time");
    FieldReader counts(fields.Prefixed("channel_message_counts"), fields.where(), source_);
    contents_.statistics_message_counts.clear();
    while (!counts.empty()) {
      const std::uint16_t channel_id = counts.U16("channel_id");
      contents_.statistics_message_counts[channel_id] = counts.U64("message_count");
    }
    contents_.statistics = stats;
  }

  // A ChunkIndex must describe a chunk read above and point at its MessageIndex records:
  // indexed readers trust it to seek.
  void ReadChunkIndex(FieldReader& fields) {
    const Where& where = fields.where();
    const std::uint64_t start_time = fields.U64("message_start_time");
    const std::uint64_t end_time = fields.U64("message_end_time");
    const std::uint64_t chunk_start = fields.U64("chunk_start_offset");
    const std::uint64_t chunk_length = fields.U64("chunk_length");
    FieldReader offsets(fields.Prefixed("message_index_offsets"), where, source_);
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    while (!offsets.empty()) {
      const std::uint16_t channel_id = offsets.U16("channel_id");
      message_index_offsets[channel_id] = offsets.U64("offset");
    }
    const std::uint64_t message_index_length = fields.U64("message_index_length");
    const std::string_view compression = fields.Prefixed("compression");
    const std::uint64_t compressed_size = fields.U64("compressed_size");
    const std::uint64_t uncompressed_size = fields.U64("uncompressed_size");

    const auto chunk = chunks_.find(chunk_start);
    if (chunk == chunks_.end()) {
      FailAt(where,
             fmt::format("chunk_start_offset {} is not where a Chunk record starts", chunk_start));
    }
    const ChunkFacts& facts = chunk->second;
    if (facts.length != chunk_length || facts.compression != compression ||
        facts.compressed_size != compressed_size || facts.uncompressed_size != uncompressed_size ||
        facts.message_start_time != start_time || facts.message_end_time != end_time) {
      FailAt(where, fmt::format("does not match the Chunk record at byte {}", chunk_start));
    }
    const std::uint64_t index_begin = chunk_start + chunk_length;
    for (const auto& [channel_id, offset] : message_index_offsets) {
      const auto index = message_indexes_.find(offset);
      if (index == message_indexes_.end() || index->second != channel_id || offset < index_begin ||
          offset - index_begin >= message_index_length) {
        FailAt(where, fmt::format("message index offset {} for channel {} is not that channel's "
                                  "MessageIndex record after the chunk",
                                  offset, channel_id));
      }
    }
  }

  // A group must cover whole summary records, all of its opcode.
  void ReadSummaryOffset(const Record& record) {
    FieldReader fields(record.content, record.where, source_);
    const std::uint8_t opcode = fields.U8("group_opcode");
    const std::uint64_t start = fields.U64("group_start");
    const std::uint64_t length = fields.U64("group_length");
    auto it = std::lower_bound(
        summary_records_.begin(), summary_records_.end(), start,
        [](const SummaryRecord& r, std::uint64_t offset) { return r.offset < offset; });
    std::uint64_t end = start;
    while (it != summary_records_.end() && it->offset == end && it->opcode == opcode &&
           end - start < length) {
      end = it->end;
      ++it;
    }
    if (length == 0 || end - start != length) {
      FailAt(record.where,
             fmt::format("group of {} records at byte {}, {} bytes long, does not match the "
                         "summary section",
                         OpcodeName(opcode), start, length));
    }
  }

  void ReadFooter(const Record& record) {
    FieldReader fields(record.content, record.where, source_);
    const std::uint64_t summary_start = fields.U64("summary_start");
    const std::uint64_t summary_offset_start = fields.U64("summary_offset_start");
    const std::uint32_t crc = fields.U32("summary_crc");
    const bool has_summary = !summary_records_.empty();
    if (summary_start != 0 && (!has_summary || summary_start != summary_start_)) {
      FailAt(record.where,
             fmt::format("summary_start {} is wrong: the summary section {}", summary_start,
                         has_summary ? fmt::format("starts at byte {}", summary_start_)
                                     : std::string("is empty")));
    }
    if (summary_offset_start != 0 && summary_offset_start != summary_offset_start_) {
      FailAt(record.where, fmt::format("summary_offset_start {} is not where the SummaryOffset "
                                       "records start",
                                       summary_offset_start));
    }
    // The CRC covers from the summary section's start through summary_offset_start.
    const std::uint64_t crc_end = record.where.offset + mcap::kRecordPrefixBytes + 16;
    const std::string_view covered =
        bytes_.substr(static_cast<std::size_t>(summary_start_),
                      static_cast<std::size_t>(crc_end - summary_start_));
    if (crc != 0 && mcap::Crc32(covered) != crc) {
      FailAt(record.where, fmt::format("summary CRC mismatch: bytes {}..{} have CRC 0x{:08x}, "
                                       "the footer says 0x{:08x} (corrupted)",
                                       summary_start_, crc_end, mcap::Crc32(covered), crc));
    }
    phase_ = Phase::kDone;
  }

  struct SummaryRecord {
    std::uint64_t offset = 0;
    std::uint64_t end = 0;
    std::uint8_t opcode = 0;
  };

  std::string_view bytes_;
  const std::string& source_;
  McapContents contents_;
  Phase phase_ = Phase::kData;

  bool message_index_may_follow_ = false;
  std::vector<ChunkMessage> chunk_messages_;                // of the last chunk, by offset
  std::map<std::uint64_t, ChunkFacts> chunks_;              // by file offset
  std::map<std::uint64_t, std::uint16_t> message_indexes_;  // file offset -> channel id

  std::uint64_t summary_start_ = 0;  // just past DataEnd, whether or not a summary follows
  std::uint64_t summary_offset_start_ = 0;
  std::vector<SummaryRecord> summary_records_;  // in file order
};

}  // namespace

McapContents ReadMcapBytes(const std::string& bytes, const std::string& source) {
  return Parser(bytes, source).Parse();
}

McapContents ReadMcapFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) Fail(path, fmt::format("cannot open: {}", std::strerror(errno)));
  const std::streamoff size = in.tellg();
  if (size < 0) Fail(path, "cannot read: not a regular file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in) Fail(path, fmt::format("cannot read: {}", std::strerror(errno)));
  return ReadMcapBytes(bytes, path);
}

}  // namespace lookout::io
