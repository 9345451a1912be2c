#pragma once

// Chunk compression for MCAP: zstd (one zstd frame), lz4 (the LZ4 *frame* format, which is what
// MCAP's "lz4" means, not the raw block format) or none. Internal to lookout::io.

#include <cstdint>
#include <string>
#include <string_view>

#include "lookout/io/mcap_writer.h"

namespace lookout::io::mcap {

// The Chunk.compression string for `compression`: "zstd", "lz4" or "".
std::string_view CompressionName(McapCompression compression);

// Deterministic: the same input gives the same bytes. Throws std::runtime_error if the
// compression library fails (it only does when out of memory).
std::string CompressChunkRecords(McapCompression compression, std::string_view records);

struct DecompressedChunk {
  std::string records;
  std::string
      problem;  // empty on success, else what is wrong, e.g. "zstd: Unknown frame descriptor"
  bool ok() const { return problem.empty(); }
};

// Decompresses chunk records that claim to be `uncompressed_size` bytes. Succeeds only if they
// decompress to exactly that many; memory grows with the bytes actually produced and never past
// uncompressed_size, so a corrupted size field cannot make it allocate more than the data holds.
// The caller bounds uncompressed_size itself (kMaxChunkUncompressedBytes).
DecompressedChunk DecompressChunkRecords(std::string_view compression, std::string_view compressed,
                                         std::uint64_t uncompressed_size);

}  // namespace lookout::io::mcap
