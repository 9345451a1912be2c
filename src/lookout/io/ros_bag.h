#pragma once

// A reader of ROS1 bag files, format version 2.0 (ROS wiki "Bags/Format/2.0").
//
// Written by hand because Debian 12 packages no C++ rosbag library outside ROS itself.
//
// What is read: the `#ROSBAG V2.0` magic; the bag header record (index_pos, conn_count,
// chunk_count); chunk records compressed with `none`, `bz2` (libbz2) or `lz4` (the LZ4 frame
// format that roslz4 writes: independent blocks, content checksum, read by liblz4's frame
// decoder); connection records (topic, type, md5sum, message_definition, callerid, latching);
// message data records inside chunks; and the index section's connection and chunk-info
// records. Index data records are skipped: a chunk is read whole and its messages come in
// record order, so their per-message offsets are not needed.
//
// With an index (the bag header's index_pos, as every closed bag has), the connections come
// from the index section and the chunk positions from the chunk infos; a chunk that holds none
// of the wanted connections is not even decompressed. Without one (a recording that was killed)
// or when the index does not hold together, the file is scanned record by record (`used_index`
// says which, `warnings` why).
//
// Errors. Outside the chunks (magic, bag header, a record header that does not parse), the bag
// is refused with lookout::InputError(file, byte position, field, problem), where the "line" is
// the 1-based position of the record's first byte in the file (offset + 1) and the problem
// repeats the offset. Inside a chunk (it does not decompress, or a record in it does not
// parse), the chunk is skipped whole and counted (`chunks_skipped`), since the other chunks
// are independent of it. A file that ends inside a record keeps what came before it and
// counts the rest (`truncated_bytes`). Sizes are checked against the bytes there before
// anything is allocated; a chunk decompresses into memory that grows with its real output, at
// most kMaxRosChunkBytes.
//
// Memory: the whole file is held (bags here are tens of MB) and one decompressed chunk at a
// time.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "lookout/io/ros_message.h"

namespace lookout::io {

inline constexpr std::uint64_t kMaxRosChunkBytes = std::uint64_t{1} << 30;

struct RosConnection {
  std::uint32_t id = 0;
  std::string topic;
  std::string type;  // "pkg/Type"
  std::string md5sum;
  std::string message_definition;
  std::string callerid;
  bool latching = false;
};

struct RosChunkInfo {
  std::uint64_t position = 0;  // of the chunk record in the file
  RosTime start_time;
  RosTime end_time;
  std::map<std::uint32_t, std::uint32_t> message_counts;  // per connection id
};

// One message data record. `data` points into the chunk being visited: it is valid during the
// visit only.
struct RosBagMessage {
  std::uint32_t connection = 0;
  RosTime time;  // the record's time: when the recorder received the message
  std::string_view data;
  std::uint64_t chunk_position = 0;
};

struct RosBagStats {
  bool used_index = false;
  std::uint64_t chunks_read = 0;
  std::uint64_t chunks_skipped = 0;            // corrupted: see warnings
  std::uint64_t chunks_not_needed = 0;         // the index says none of the wanted connections
  std::uint64_t messages_unknown_connection = 0;  // skipped
  std::uint64_t records_unknown_op = 0;        // skipped, as newer formats may add some
  std::uint64_t truncated_bytes = 0;           // the file ends inside a record: bytes ignored
  std::vector<std::string> warnings;           // one line per skip or fallback
};

class RosBag {
 public:
  // Parses the magic, the bag header and the index (or scans the records without one).
  // `source` names the bytes in errors. Throws lookout::InputError.
  RosBag(std::string bytes, std::string source);

  // Reads a .bag file, or the single .bag inside a .zip archive (see zip_entry.h).
  static RosBag Open(const std::string& path);

  const std::string& source() const { return source_; }
  // Every connection known so far: all of them with an index; without one, those at the top
  // level plus those met inside the chunks visited so far.
  const std::map<std::uint32_t, RosConnection>& connections() const { return connections_; }
  const std::vector<RosChunkInfo>& chunk_infos() const { return chunk_infos_; }
  const RosBagStats& stats() const { return stats_; }

  using Visitor = std::function<void(const RosConnection&, const RosBagMessage&)>;
  // Visits the messages chunk by chunk in file order, each chunk decompressed alone. With
  // `wanted` (connection ids), only those; chunks whose index shows none of them are skipped
  // without decompressing.
  void ForEachMessage(const Visitor& visit, const std::set<std::uint32_t>* wanted = nullptr);

 private:
  struct ChunkRef {
    std::uint64_t position = 0;
    bool indexed = false;
    std::set<std::uint32_t> connections;  // from the chunk info, when indexed
  };

  bool ReadIndex(std::uint64_t index_position, std::uint32_t connection_count,
                 std::uint32_t chunk_count);
  void ScanRecords(std::uint64_t first_record);
  void VisitChunk(const ChunkRef& chunk, const Visitor& visit,
                  const std::set<std::uint32_t>* wanted);

  std::string bytes_;
  std::string source_;
  std::map<std::uint32_t, RosConnection> connections_;
  std::vector<RosChunkInfo> chunk_infos_;
  std::vector<ChunkRef> chunks_;
  RosBagStats stats_;
};

}  // namespace lookout::io
