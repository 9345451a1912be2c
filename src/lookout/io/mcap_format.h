#pragma once

// Constants of the MCAP format (https://mcap.dev/spec, major version 0) shared by McapWriter and
// the MCAP reader. Internal to lookout::io: nothing outside this module includes it.

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string_view>

namespace lookout::io::mcap {

inline constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};

// Record opcodes, spec section "Records".
enum class Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Every record starts with its opcode (1 byte) and content length (uint64).
inline constexpr std::uint64_t kRecordPrefixBytes = 1 + 8;
// Footer content: summary_start, summary_offset_start, summary_crc.
inline constexpr std::uint64_t kFooterContentBytes = 8 + 8 + 4;

// Chunk.compression values; the empty string means uncompressed.
inline constexpr std::string_view kCompressionZstd = "zstd";
inline constexpr std::string_view kCompressionLz4 = "lz4";

// The largest chunk the reader will decompress. A corrupted uncompressed_size could otherwise ask
// for any amount of memory; Lookout writes 1 MiB chunks, other writers rarely exceed tens of MiB.
inline constexpr std::uint64_t kMaxChunkUncompressedBytes = std::uint64_t{1} << 30;

// zlib's CRC-32, the one MCAP uses. crc32() takes a 32-bit length, hence the loop.
inline std::uint32_t Crc32(std::string_view bytes, std::uint32_t crc = 0) {
  uLong value = crc;
  while (!bytes.empty()) {
    const std::size_t n = std::min<std::size_t>(bytes.size(), std::numeric_limits<uInt>::max());
    value = ::crc32(value, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(n));
    bytes.remove_prefix(n);
  }
  return static_cast<std::uint32_t>(value);
}

}  // namespace lookout::io::mcap
