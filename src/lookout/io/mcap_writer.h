#pragma once

// A writer of MCAP files (https://mcap.dev/spec, version 0). No Debian package ships an MCAP
// library, so Lookout has its own, small and tested against the reference TypeScript reader
// (tests/node). It writes: magic, Header, chunked Schema/Channel/Message records (zstd, lz4 or
// none) each followed by its MessageIndex records, then DataEnd, a summary section (Schema,
// Channel, Statistics, ChunkIndex records), SummaryOffset records, Footer and magic: what
// Foxglove needs to open and seek a file. No wall-clock time is written anywhere, so the same
// messages give the same bytes.
//
// The file is written to PATH.part and renamed to PATH by Finish(): a run that fails leaves no
// half-written recording behind.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>

#include "lookout/core/time.h"

namespace lookout::io {

enum class McapCompression { kNone, kZstd, kLz4 };

struct McapWriterOptions {
  McapCompression compression = McapCompression::kZstd;
  std::size_t chunk_size_bytes = 1 << 20;  // uncompressed bytes before a chunk is closed
  std::string profile;                     // Header.profile; empty for none
  std::string library = "lookout";         // Header.library
};

class McapWriter {
 public:
  // Opens PATH.part for writing; throws std::runtime_error if it cannot.
  McapWriter(std::string path, McapWriterOptions options = {});
  ~McapWriter();  // without Finish(): removes PATH.part
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // Returns the schema id (>= 1). `encoding` e.g. "jsonschema"; `data` the schema text.
  std::uint16_t AddSchema(std::string_view name, std::string_view encoding, std::string_view data);
  // Returns the channel id (>= 1). `message_encoding` e.g. "json". schema_id 0 means schemaless.
  // Schema and Channel records go into the open chunk and again into the summary.
  std::uint16_t AddChannel(std::uint16_t schema_id, std::string_view topic,
                           std::string_view message_encoding,
                           const std::unordered_map<std::string, std::string>& metadata = {});
  // Messages may come in any log-time order; chunk and summary times are kept right. Each
  // message's MCAP sequence number is its index among its channel's messages (0, 1, 2, ...).
  // Throws std::invalid_argument for an unknown channel or a negative time.
  void Write(std::uint16_t channel_id, TimeNs log_time, TimeNs publish_time,
             std::string_view data);
  // Flushes the last chunk, writes the summary and footer, renames PATH.part to PATH.
  void Finish();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lookout::io
