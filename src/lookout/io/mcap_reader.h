#pragma once

// Reads the MCAP files that McapWriter writes (and any conforming file using zstd, lz4 or no
// chunk compression). It checks the magic, every record's length, the chunk CRCs and the
// data-section CRC where present; a truncated or corrupted file throws lookout::InputError
// naming the file and what is wrong, never reads out of bounds.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lookout/core/time.h"

namespace lookout::io {

struct McapSchema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;
  std::string data;
};

struct McapChannel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
};

struct McapMessage {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  TimeNs log_time = 0;
  TimeNs publish_time = 0;
  std::string data;
};

struct McapContents {
  std::string profile;
  std::string library;
  std::map<std::uint16_t, McapSchema> schemas;
  std::map<std::uint16_t, McapChannel> channels;
  std::vector<McapMessage> messages;  // in file order
  std::map<std::uint16_t, std::uint64_t> statistics_message_counts;  // from the summary
  std::uint32_t chunk_count = 0;
};

// Reads a whole file into memory (recordings here are small: minutes of 2D sensors).
McapContents ReadMcapFile(const std::string& path);
// Same, from bytes; `source` names them in errors. Used by the fuzz target.
McapContents ReadMcapBytes(const std::string& bytes, const std::string& source);

}  // namespace lookout::io
