#pragma once

// Reads the MCAP files that McapWriter writes (and any conforming file using zstd, lz4 or no
// chunk compression). It checks the magic, every record's length, the chunk CRCs and the
// data-section and summary CRCs where present, and that the summary's indexes (chunk indexes,
// message indexes, summary offsets) point at the records they claim, so a file it accepts can
// also be read by seeking. A truncated or corrupted file throws lookout::InputError naming the
// file and what is wrong (with the byte offset), never reads out of bounds, and never allocates
// more than a chunk really decompresses to (at most 1 GiB per chunk).
//
// Attachments and Metadata records are skipped; unknown record opcodes are skipped, as the spec
// asks. Timestamps above 2^63 - 1 ns are refused (TimeNs is signed).

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/time.h"

namespace lookout::io {

struct McapSchema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;
  std::string data;
  bool operator==(const McapSchema&) const = default;
};

struct McapChannel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
  bool operator==(const McapChannel&) const = default;
};

struct McapMessage {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  TimeNs log_time = 0;
  TimeNs publish_time = 0;
  std::string data;
  bool operator==(const McapMessage&) const = default;
};

// The summary section's Statistics record, as written.
struct McapStatistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  TimeNs message_start_time = 0;  // 0 when there are no messages
  TimeNs message_end_time = 0;
};

struct McapContents {
  std::string profile;
  std::string library;
  std::map<std::uint16_t, McapSchema> schemas;
  std::map<std::uint16_t, McapChannel> channels;
  std::vector<McapMessage> messages;  // in file order
  std::map<std::uint16_t, std::uint64_t> statistics_message_counts;  // from the summary
  // Chunk records found in the data section.
  std::uint32_t chunk_count = 0;
  // Absent when the file has no Statistics record.
  std::optional<McapStatistics> statistics;
};

// Reads a whole file into memory (recordings here are small: minutes of 2D sensors).
McapContents ReadMcapFile(const std::string& path);
// Same, from bytes; `source` names them in errors. Used by the fuzz target.
McapContents ReadMcapBytes(const std::string& bytes, const std::string& source);

}  // namespace lookout::io
