#include "lookout/io/ros_bag.h"

#include <bzlib.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "lookout/core/input_error.h"
#include "lookout/io/file_bytes.h"
#include "lookout/io/little_endian.h"
#include "lookout/io/mcap_compression.h"
#include "lookout/io/zip_entry.h"

namespace lookout::io {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";

// Record opcodes (the `op` header field).
constexpr std::uint8_t kOpMessageData = 0x02;
constexpr std::uint8_t kOpBagHeader = 0x03;
constexpr std::uint8_t kOpIndexData = 0x04;
constexpr std::uint8_t kOpChunk = 0x05;
constexpr std::uint8_t kOpChunkInfo = 0x06;
constexpr std::uint8_t kOpConnection = 0x07;

constexpr std::uint32_t kChunkInfoVersion = 1;
constexpr std::size_t kInitialChunkBytes = std::size_t{1} << 16;

// A record that is there in full but does not parse.
struct RecordError {
  std::string field;
  std::string problem;
};

// Header fields of a record, or the fields of a connection header: `len name=value` repeated.
class Fields {
 public:
  Fields(std::string_view bytes, std::string_view what) : what_(what) {
    while (!bytes.empty()) {
      if (bytes.size() < 4) Fail("", "a field's length runs past the header's end");
      const auto length = LoadLittleEndian<std::uint32_t>(bytes.data());
      bytes.remove_prefix(4);
      if (length > bytes.size()) {
        Fail("", fmt::format("a field of {} bytes runs past the header's end", length));
      }
      const std::string_view field = bytes.substr(0, length);
      bytes.remove_prefix(length);
      const std::size_t equals = field.find('=');
      if (equals == std::string_view::npos) Fail("", "a field without '='");
      // A repeated name: the last one counts, as in rosbag's own reader.
      fields_.insert_or_assign(field.substr(0, equals), field.substr(equals + 1));
    }
  }

  std::optional<std::string_view> Find(std::string_view name) const {
    const auto it = fields_.find(name);
    if (it == fields_.end()) return std::nullopt;
    return it->second;
  }

  std::string_view Bytes(std::string_view name, std::size_t size) const {
    const std::optional<std::string_view> value = Find(name);
    if (!value) Fail(name, "missing");
    if (size != 0 && value->size() != size) {
      Fail(name, fmt::format("is {} bytes, not {}", value->size(), size));
    }
    return *value;
  }

  std::string String(std::string_view name) const { return std::string(Bytes(name, 0)); }
  std::uint32_t U32(std::string_view name) const {
    return LoadLittleEndian<std::uint32_t>(Bytes(name, 4).data());
  }
  std::uint64_t U64(std::string_view name) const {
    return LoadLittleEndian<std::uint64_t>(Bytes(name, 8).data());
  }
  RosTime Time(std::string_view name) const {
    const char* p = Bytes(name, 8).data();
    return RosTime{LoadLittleEndian<std::uint32_t>(p), LoadLittleEndian<std::uint32_t>(p + 4)};
  }

  [[noreturn]] void Fail(std::string_view name, const std::string& problem) const {
    throw RecordError{name.empty() ? std::string(what_) : fmt::format("{}.{}", what_, name),
                      problem};
  }

 private:
  std::string_view what_;
  std::map<std::string_view, std::string_view, std::less<>> fields_;
};

struct BagRecord {
  std::uint8_t op = 0;
  Fields header;
  std::string_view data;
  std::uint64_t end = 0;  // position just past the record
};

// The record at `position` of `bytes`, or nullopt when `bytes` ends inside it. Throws
// RecordError when its header does not parse.
std::optional<BagRecord> ReadRecord(std::string_view bytes, std::uint64_t position) {
  if (position > bytes.size()) return std::nullopt;
  std::string_view rest = bytes.substr(static_cast<std::size_t>(position));
  if (rest.size() < 4) return std::nullopt;
  const auto header_length = LoadLittleEndian<std::uint32_t>(rest.data());
  rest.remove_prefix(4);
  if (header_length > rest.size() || rest.size() - header_length < 4) return std::nullopt;
  Fields header(rest.substr(0, header_length), "record header");
  rest.remove_prefix(header_length);
  const auto data_length = LoadLittleEndian<std::uint32_t>(rest.data());
  rest.remove_prefix(4);
  if (data_length > rest.size()) return std::nullopt;
  const std::string_view op = header.Bytes("op", 1);
  return BagRecord{static_cast<std::uint8_t>(op.front()), std::move(header),
                rest.substr(0, data_length),
                position + 8 + std::uint64_t{header_length} + data_length};
}

RosConnection ParseConnection(const BagRecord& record) {
  RosConnection c;
  c.id = record.header.U32("conn");
  c.topic = record.header.String("topic");
  const Fields data(record.data, "connection header");
  c.type = data.String("type");
  c.md5sum = data.String("md5sum");
  c.message_definition = data.String("message_definition");
  if (const auto callerid = data.Find("callerid")) c.callerid = std::string(*callerid);
  if (const auto latching = data.Find("latching")) c.latching = *latching == "1";
  return c;
}

struct Decompressed {
  std::string records;
  std::string problem;
};

// bz2 into a buffer that grows with the real output, refusing anything but exactly `size`.
Decompressed DecompressBz2(std::string_view compressed, std::uint64_t size) {
  Decompressed result;
  bz_stream stream{};
  if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK) throw std::bad_alloc();
  const auto limit = static_cast<std::size_t>(size);
  std::string& out = result.records;
  out.resize(std::min(limit, std::max(kInitialChunkBytes, 4 * compressed.size())));
  std::size_t used = 0;
  stream.next_in = const_cast<char*>(compressed.data());
  stream.avail_in = static_cast<unsigned int>(compressed.size());
  int status = BZ_OK;
  while (status != BZ_STREAM_END) {
    if (used == out.size()) {
      if (out.size() >= limit) {
        // Full: one more byte of output would exceed the declared size.
        char extra = 0;
        stream.next_out = &extra;
        stream.avail_out = 1;
        status = BZ2_bzDecompress(&stream);
        if (stream.avail_out == 0) {
          result.problem =
              fmt::format("bz2: decompresses to more than the {} bytes declared", size);
        }
        break;
      }
      out.resize(std::min(limit, 2 * out.size() + 1));
    }
    const std::size_t room =
        std::min<std::size_t>(out.size() - used, std::numeric_limits<unsigned int>::max());
    stream.next_out = out.data() + used;
    stream.avail_out = static_cast<unsigned int>(room);
    status = BZ2_bzDecompress(&stream);
    used += room - stream.avail_out;
    if (status != BZ_OK && status != BZ_STREAM_END) {
      result.problem = fmt::format("bz2: the stream is corrupt (error {})", status);
      break;
    }
    if (status == BZ_OK && stream.avail_in == 0 && stream.avail_out != 0) {
      result.problem = "bz2: the stream is cut short";
      break;
    }
  }
  BZ2_bzDecompressEnd(&stream);
  if (result.problem.empty() && status != BZ_STREAM_END) {
    result.problem = "bz2: the stream is cut short";
  }
  if (result.problem.empty() && stream.avail_in != 0) {
    result.problem = fmt::format("bz2: {} bytes after the end of the stream", stream.avail_in);
  }
  if (result.problem.empty() && used != limit) {
    result.problem = fmt::format("decompresses to {} bytes, the chunk says {}", used, size);
  }
  out.resize(used);
  return result;
}

Decompressed DecompressChunk(std::string_view compression, std::string_view data,
                             std::uint64_t size) {
  if (size > kMaxRosChunkBytes) {
    return {{}, fmt::format("declares {} bytes, more than the {} Lookout reads", size,
                            kMaxRosChunkBytes)};
  }
  if (compression == "none") {
    if (data.size() != size) {
      return {{}, fmt::format("holds {} bytes, the chunk says {}", data.size(), size)};
    }
    return {std::string(data), {}};
  }
  if (compression == "bz2") return DecompressBz2(data, size);
  if (compression == "lz4") {
    // roslz4 writes the LZ4 frame format, so the MCAP reader's bounded frame decoder reads it.
    mcap::DecompressedChunk chunk = mcap::DecompressChunkRecords("lz4", data, size);
    return {std::move(chunk.records), std::move(chunk.problem)};
  }
  return {{}, fmt::format("unknown compression '{}' (Lookout reads none, bz2 and lz4)",
                          compression)};
}

int BytePosition(std::uint64_t offset) {
  return static_cast<int>(
      std::min<std::uint64_t>(offset + 1, std::uint64_t{std::numeric_limits<int>::max()}));
}

[[noreturn]] void Refuse(const std::string& source, std::uint64_t offset, const std::string& field,
                         const std::string& problem) {
  throw InputError(source, BytePosition(offset), field,
                   fmt::format("{} (byte offset {})", problem, offset));
}

}  // namespace

RosBag::RosBag(std::string bytes, std::string source)
    : bytes_(std::move(bytes)), source_(std::move(source)) {
  if (std::string_view(bytes_).substr(0, kMagic.size()) != kMagic) {
    Refuse(source_, 0, "magic", "not a ROS1 bag v2.0: the file does not start with '#ROSBAG V2.0'");
  }
  std::optional<BagRecord> header;
  try {
    header = ReadRecord(bytes_, kMagic.size());
    if (!header) {
      Refuse(source_, kMagic.size(), "bag header", "the file ends inside the bag header");
    }
    if (header->op != kOpBagHeader) {
      Refuse(source_, kMagic.size(), "bag header.op", fmt::format("is {}, not 3", header->op));
    }
    const std::uint64_t index_position = header->header.U64("index_pos");
    const std::uint32_t connection_count = header->header.U32("conn_count");
    const std::uint32_t chunk_count = header->header.U32("chunk_count");
    if (index_position == 0) {
      stats_.warnings.push_back("no index (index_pos is 0: the recording was not closed)");
    } else if (index_position < header->end || index_position >= bytes_.size()) {
      stats_.warnings.push_back(fmt::format(
          "index_pos {} is outside the file's {} bytes of records", index_position, bytes_.size()));
    } else {
      stats_.used_index = ReadIndex(index_position, connection_count, chunk_count);
    }
  } catch (const RecordError& e) {
    Refuse(source_, kMagic.size(), "bag header", fmt::format("{}: {}", e.field, e.problem));
  }
  if (!stats_.used_index) {
    connections_.clear();
    chunk_infos_.clear();
    chunks_.clear();
    ScanRecords(header->end);
  }
}

RosBag RosBag::Open(const std::string& path) {
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".zip") == 0) {
    return RosBag(ReadSingleZipEntry(path).data, path);
  }
  return RosBag(ReadFileBytes(path), path);
}

bool RosBag::ReadIndex(std::uint64_t index_position, std::uint32_t connection_count,
                       std::uint32_t chunk_count) {
  std::uint64_t position = index_position;
  try {
    while (position < bytes_.size()) {
      const std::optional<BagRecord> record = ReadRecord(bytes_, position);
      if (!record) throw RecordError{"index", "the file ends inside an index record"};
      if (record->op == kOpConnection) {
        RosConnection connection = ParseConnection(*record);
        const std::uint32_t id = connection.id;
        connections_.insert_or_assign(id, std::move(connection));
      } else if (record->op == kOpChunkInfo) {
        if (record->header.U32("ver") != kChunkInfoVersion) {
          throw RecordError{"chunk info.ver", "is not 1"};
        }
        RosChunkInfo info;
        info.position = record->header.U64("chunk_pos");
        info.start_time = record->header.Time("start_time");
        info.end_time = record->header.Time("end_time");
        const std::uint32_t count = record->header.U32("count");
        if (record->data.size() != std::size_t{count} * 8) {
          throw RecordError{"chunk info.count", "does not match the record's data"};
        }
        for (std::uint32_t i = 0; i < count; ++i) {
          const char* p = record->data.data() + std::size_t{i} * 8;
          info.message_counts[LoadLittleEndian<std::uint32_t>(p)] =
              LoadLittleEndian<std::uint32_t>(p + 4);
        }
        if (info.position < kMagic.size() || info.position >= index_position) {
          throw RecordError{"chunk info.chunk_pos", "points outside the chunk section"};
        }
        chunk_infos_.push_back(std::move(info));
      } else {
        throw RecordError{"index", fmt::format("unexpected record op {}", record->op)};
      }
      position = record->end;
    }
    if (connections_.size() != connection_count || chunk_infos_.size() != chunk_count) {
      throw RecordError{"index", fmt::format("holds {} connections and {} chunk infos, the bag "
                                             "header says {} and {}",
                                             connections_.size(), chunk_infos_.size(),
                                             connection_count, chunk_count)};
    }
  } catch (const RecordError& e) {
    stats_.warnings.push_back(fmt::format("index unusable at byte {}: {}: {}; scanning the records",
                                          position, e.field, e.problem));
    return false;
  }
  std::sort(chunk_infos_.begin(), chunk_infos_.end(),
            [](const RosChunkInfo& a, const RosChunkInfo& b) { return a.position < b.position; });
  for (const RosChunkInfo& info : chunk_infos_) {
    ChunkRef chunk{info.position, true, {}};
    for (const auto& [id, count] : info.message_counts) {
      if (count > 0) chunk.connections.insert(id);
    }
    chunks_.push_back(std::move(chunk));
  }
  return true;
}

void RosBag::ScanRecords(std::uint64_t first_record) {
  std::uint64_t position = first_record;
  while (position < bytes_.size()) {
    std::optional<BagRecord> record;
    try {
      record = ReadRecord(bytes_, position);
      if (!record) {
        stats_.truncated_bytes = bytes_.size() - position;
        stats_.warnings.push_back(fmt::format(
            "the file ends inside the record at byte {}: its last {} bytes are ignored", position,
            stats_.truncated_bytes));
        return;
      }
      switch (record->op) {
        case kOpChunk:
          chunks_.push_back(ChunkRef{position, false, {}});
          break;
        case kOpConnection: {
          RosConnection connection = ParseConnection(*record);
          const std::uint32_t id = connection.id;
          connections_.insert_or_assign(id, std::move(connection));
          break;
        }
        case kOpIndexData:
        case kOpChunkInfo:
          break;  // the index is what failed; the records themselves suffice
        default:
          ++stats_.records_unknown_op;
          break;
      }
    } catch (const RecordError& e) {
      Refuse(source_, position, e.field, e.problem);
    }
    position = record->end;
  }
}

void RosBag::ForEachMessage(const Visitor& visit, const std::set<std::uint32_t>* wanted) {
  for (const ChunkRef& chunk : chunks_) {
    if (wanted != nullptr && chunk.indexed &&
        std::none_of(chunk.connections.begin(), chunk.connections.end(),
                     [&](std::uint32_t id) { return wanted->count(id) != 0; })) {
      ++stats_.chunks_not_needed;
      continue;
    }
    VisitChunk(chunk, visit, wanted);
  }
}

void RosBag::VisitChunk(const ChunkRef& chunk, const Visitor& visit,
                        const std::set<std::uint32_t>* wanted) {
  std::string records;
  std::vector<RosBagMessage> messages;
  std::vector<RosConnection> new_connections;
  std::uint64_t inner = 0;
  try {
    const std::optional<BagRecord> record = ReadRecord(bytes_, chunk.position);
    if (!record) throw RecordError{"chunk", "the file ends inside it"};
    if (record->op != kOpChunk) {
      throw RecordError{"chunk.op", fmt::format("is {}, not 5 (a chunk)", record->op)};
    }
    Decompressed d = DecompressChunk(record->header.Bytes("compression", 0), record->data,
                                     record->header.U32("size"));
    if (!d.problem.empty()) throw RecordError{"chunk.data", d.problem};
    records = std::move(d.records);
    while (inner < records.size()) {
      const std::optional<BagRecord> r = ReadRecord(records, inner);
      if (!r) throw RecordError{"chunk record", "runs past the chunk's end"};
      if (r->op == kOpMessageData) {
        const char* time = r->header.Bytes("time", 8).data();
        messages.push_back(RosBagMessage{r->header.U32("conn"),
                                         RosTime{LoadLittleEndian<std::uint32_t>(time),
                                                 LoadLittleEndian<std::uint32_t>(time + 4)},
                                         r->data, chunk.position});
      } else if (r->op == kOpConnection) {
        new_connections.push_back(ParseConnection(*r));
      } else {
        ++stats_.records_unknown_op;
      }
      inner = r->end;
    }
  } catch (const RecordError& e) {
    ++stats_.chunks_skipped;
    stats_.warnings.push_back(
        fmt::format("chunk at byte {} skipped: {}: {} (byte {} of its records)", chunk.position,
                    e.field, e.problem, inner));
    return;
  }
  ++stats_.chunks_read;
  for (RosConnection& connection : new_connections) {
    const std::uint32_t id = connection.id;
    connections_.try_emplace(id, std::move(connection));
  }
  for (const RosBagMessage& message : messages) {
    if (wanted != nullptr && wanted->count(message.connection) == 0) continue;
    const auto connection = connections_.find(message.connection);
    if (connection == connections_.end()) {
      ++stats_.messages_unknown_connection;
      continue;
    }
    visit(connection->second, message);
  }
}

}  // namespace lookout::io
