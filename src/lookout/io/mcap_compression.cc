#include "lookout/io/mcap_compression.h"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "lookout/io/mcap_format.h"

namespace lookout::io::mcap {
namespace {

// zstd's own default; higher levels cost much more time for a few percent on sensor data.
constexpr int kZstdLevel = 3;
// First output allocation; doubled as the decoder fills it, up to uncompressed_size.
constexpr std::size_t kInitialOutputBytes = std::size_t{64} << 10;

struct StepResult {
  std::size_t consumed = 0;
  std::size_t produced = 0;
  bool frame_done = false;  // the decoder ended a frame exactly at the bytes consumed so far
  std::string error;
};

// Runs a streaming decoder until all input is consumed. `step(in, out, out_size)` decodes some
// of `in` into `out`. The output buffer is grown only when the decoder has filled it, so memory
// follows real output; past uncompressed_size the data is rejected.
template <typename Step>
DecompressedChunk DecodeBounded(std::string_view compressed, std::uint64_t uncompressed_size,
                                Step step) {
  DecompressedChunk result;
  const auto limit = static_cast<std::size_t>(uncompressed_size);
  std::string& out = result.records;
  out.resize(std::min(limit, std::max(kInitialOutputBytes, 4 * compressed.size())));
  std::size_t used = 0;
  bool frame_done = false;
  while (!(frame_done && compressed.empty())) {
    if (used == out.size() && out.size() < limit) {
      out.resize(std::min(limit, 2 * out.size() + 1));
    }
    const StepResult s = step(compressed, out.data() + used, out.size() - used);
    if (!s.error.empty()) {
      result.problem = s.error;
      return result;
    }
    compressed.remove_prefix(s.consumed);
    used += s.produced;
    frame_done = s.frame_done;
    if (s.consumed == 0 && s.produced == 0 && !(frame_done && compressed.empty())) {
      result.problem = used == limit
                           ? fmt::format("decompresses to more than uncompressed_size {} bytes",
                                         uncompressed_size)
                           : fmt::format("compressed data ends after {} of {} bytes, mid-frame",
                                         used, uncompressed_size);
      return result;
    }
  }
  if (used != limit) {
    result.problem =
        fmt::format("decompresses to {} bytes, uncompressed_size says {}", used, uncompressed_size);
  }
  out.resize(used);
  return result;
}

DecompressedChunk DecompressZstd(std::string_view compressed, std::uint64_t uncompressed_size) {
  const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(),
                                                                     &ZSTD_freeDCtx);
  if (!context) throw std::bad_alloc();
  return DecodeBounded(
      compressed, uncompressed_size, [&](std::string_view in, char* out, std::size_t out_size) {
        ZSTD_inBuffer input{in.data(), in.size(), 0};
        ZSTD_outBuffer output{out, out_size, 0};
        const std::size_t hint = ZSTD_decompressStream(context.get(), &output, &input);
        StepResult s;
        if (ZSTD_isError(hint) != 0) {
          s.error = fmt::format("zstd: {}", ZSTD_getErrorName(hint));
          return s;
        }
        s.consumed = input.pos;
        s.produced = output.pos;
        s.frame_done = hint == 0;
        return s;
      });
}

DecompressedChunk DecompressLz4(std::string_view compressed, std::uint64_t uncompressed_size) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)) != 0) {
    throw std::bad_alloc();
  }
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  return DecodeBounded(
      compressed, uncompressed_size, [&](std::string_view in, char* out, std::size_t out_size) {
        std::size_t consumed = in.size();
        std::size_t produced = out_size;
        const std::size_t hint =
            LZ4F_decompress(context.get(), out, &produced, in.data(), &consumed, nullptr);
        StepResult s;
        if (LZ4F_isError(hint) != 0) {
          s.error = fmt::format("lz4: {}", LZ4F_getErrorName(hint));
          return s;
        }
        s.consumed = consumed;
        s.produced = produced;
        s.frame_done = hint == 0;
        return s;
      });
}

}  // namespace

std::string_view CompressionName(McapCompression compression) {
  switch (compression) {
    case McapCompression::kZstd:
      return kCompressionZstd;
    case McapCompression::kLz4:
      return kCompressionLz4;
    case McapCompression::kNone:
      break;
  }
  return {};
}

std::string CompressChunkRecords(McapCompression compression, std::string_view records) {
  std::string out;
  switch (compression) {
    case McapCompression::kNone:
      out.assign(records);
      break;
    case McapCompression::kZstd: {
      out.resize(ZSTD_compressBound(records.size()));
      const std::size_t n =
          ZSTD_compress(out.data(), out.size(), records.data(), records.size(), kZstdLevel);
      if (ZSTD_isError(n) != 0) {
        throw std::runtime_error(fmt::format("zstd compression failed: {}", ZSTD_getErrorName(n)));
      }
      out.resize(n);
      break;
    }
    case McapCompression::kLz4: {
      // Default preferences: 64 KiB independent blocks, no checksums (the chunk has its own CRC).
      out.resize(LZ4F_compressFrameBound(records.size(), nullptr));
      const std::size_t n =
          LZ4F_compressFrame(out.data(), out.size(), records.data(), records.size(), nullptr);
      if (LZ4F_isError(n) != 0) {
        throw std::runtime_error(fmt::format("lz4 compression failed: {}", LZ4F_getErrorName(n)));
      }
      out.resize(n);
      break;
    }
  }
  return out;
}

DecompressedChunk DecompressChunkRecords(std::string_view compression, std::string_view compressed,
                                         std::uint64_t uncompressed_size) {
  if (compression.empty()) {
    DecompressedChunk result;
    if (compressed.size() != uncompressed_size) {
      result.problem = fmt::format("uncompressed records are {} bytes, uncompressed_size says {}",
                                   compressed.size(), uncompressed_size);
    } else {
      result.records.assign(compressed);
    }
    return result;
  }
  if (compression == kCompressionZstd) return DecompressZstd(compressed, uncompressed_size);
  if (compression == kCompressionLz4) return DecompressLz4(compressed, uncompressed_size);
  DecompressedChunk result;
  result.problem = "unsupported compression (Lookout reads zstd, lz4 or none)";
  return result;
}

}  // namespace lookout::io::mcap
