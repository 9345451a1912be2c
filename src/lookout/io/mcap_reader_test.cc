#include "lookout/io/mcap_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <fmt/format.h>

#include "lookout/core/input_error.h"
#include "lookout/io/mcap_compression.h"
#include "lookout/io/mcap_format.h"
#include "lookout/io/mcap_test_support.h"
#include "lookout/io/mcap_writer.h"

namespace lookout::io {
namespace {

using ::testing::HasSubstr;
using testing_support::ReadBytes;
using testing_support::ReadLe;
using testing_support::TempDir;
using testing_support::WriteSample;

// Hand-built records, for files McapWriter would never write.
std::string Le(std::uint64_t value, std::size_t width) {
  std::string out;
  for (std::size_t i = 0; i < width; ++i)
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
  return out;
}
std::string Str(std::string_view s) { return Le(s.size(), 4) + std::string(s); }
std::string Rec(std::uint8_t opcode, const std::string& content) {
  return std::string(1, static_cast<char>(opcode)) + Le(content.size(), 8) + content;
}
std::string Schema(std::uint16_t id) {
  return Rec(0x03, Le(id, 2) + Str("S") + Str("jsonschema") + Str("{}"));
}
std::string Channel(std::uint16_t id, std::uint16_t schema_id) {
  return Rec(0x04, Le(id, 2) + Le(schema_id, 2) + Str("/x") + Str("json") + Le(0, 4));
}
std::string Message(std::uint16_t channel_id, std::uint64_t log_time, std::string_view data) {
  return Rec(0x05,
             Le(channel_id, 2) + Le(9, 4) + Le(log_time, 8) + Le(log_time, 8) + std::string(data));
}
std::string Chunk(std::string_view compression, const std::string& stored,
                  std::uint64_t uncompressed_size, std::uint32_t crc) {
  return Rec(0x06, Le(0, 8) + Le(100, 8) + Le(uncompressed_size, 8) + Le(crc, 4) +
                       Str(compression) + Le(stored.size(), 8) + stored);
}
// Magic, Header, the given data records, DataEnd and Footer without CRCs or summary, magic.
std::string FileWith(const std::string& data_records) {
  return std::string(mcap::kMagic) + Rec(0x01, Str("") + Str("hand")) + data_records +
         Rec(0x0F, Le(0, 4)) + Rec(0x02, Le(0, 8) + Le(0, 8) + Le(0, 4)) +
         std::string(mcap::kMagic);
}

std::string ErrorOf(const std::string& bytes) {
  try {
    ReadMcapBytes(bytes, "test.mcap");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string SampleBytes(McapCompression compression, int message_count) {
  TempDir dir;
  const std::string path = dir.File("sample.mcap");
  McapWriterOptions options;
  options.compression = compression;
  options.chunk_size_bytes = 200;
  McapWriter writer(path, options);
  WriteSample(writer, message_count);
  writer.Finish();
  return ReadBytes(path);
}

TEST(McapReaderTest, ReadsUnchunkedFileWithoutSummary) {
  const McapContents contents = ReadMcapBytes(
      FileWith(Schema(1) + Channel(5, 1) + Rec(0x80, "ext") + Message(5, 10, "payload")),
      "hand.mcap");
  EXPECT_EQ(contents.library, "hand");
  ASSERT_EQ(contents.schemas.size(), 1u);
  ASSERT_EQ(contents.channels.size(), 1u);
  EXPECT_EQ(contents.channels.at(5).topic, "/x");
  ASSERT_EQ(contents.messages.size(), 1u);
  EXPECT_EQ(contents.messages[0].sequence, 9u);
  EXPECT_EQ(contents.messages[0].log_time, 10);
  EXPECT_EQ(contents.messages[0].data, "payload");
  EXPECT_FALSE(contents.statistics.has_value());
  EXPECT_EQ(contents.chunk_count, 0u);
}

TEST(McapReaderTest, ReadsUncompressedHandBuiltChunk) {
  const std::string records = Schema(1) + Channel(2, 1) + Message(2, 50, "a");
  const McapContents contents = ReadMcapBytes(
      FileWith(Chunk("", records, records.size(), mcap::Crc32(records))), "hand.mcap");
  ASSERT_EQ(contents.messages.size(), 1u);
  EXPECT_EQ(contents.chunk_count, 1u);
}

class McapReaderCorruption : public ::testing::TestWithParam<McapCompression> {};

TEST_P(McapReaderCorruption, EveryTruncationIsRefused) {
  const std::string bytes = SampleBytes(GetParam(), 12);
  ASSERT_NO_THROW(ReadMcapBytes(bytes, "whole.mcap"));
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_THROW(ReadMcapBytes(bytes.substr(0, n), "cut.mcap"), InputError)
        << "prefix of " << n << " of " << bytes.size() << " bytes was accepted";
  }
}

TEST_P(McapReaderCorruption, EveryFlippedByteIsRefused) {
  const std::string bytes = SampleBytes(GetParam(), 12);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::string corrupt = bytes;
    corrupt[i] = static_cast<char>(corrupt[i] ^ 0x10);
    EXPECT_THROW(ReadMcapBytes(corrupt, "flipped.mcap"), InputError)
        << "flipping byte " << i << " of " << bytes.size() << " went unnoticed";
  }
}

INSTANTIATE_TEST_SUITE_P(AllCompressions, McapReaderCorruption,
                         ::testing::Values(McapCompression::kNone, McapCompression::kZstd,
                                           McapCompression::kLz4),
                         [](const auto& param_info) { return CompressionLabel(param_info.param); });

TEST(McapReaderTest, TruncationNamesTheRecordAndSizes) {
  const std::string bytes = SampleBytes(McapCompression::kZstd, 12);
  // The first record after the Header is a Chunk; cut the file 10 bytes into its content.
  const std::size_t header_end = 8 + 9 + static_cast<std::size_t>(ReadLe(bytes, 9, 8));
  ASSERT_EQ(bytes[header_end], 0x06);
  const std::string error = ErrorOf(bytes.substr(0, header_end + 9 + 10));
  EXPECT_THAT(error, HasSubstr("test.mcap: "));
  EXPECT_THAT(error,
              HasSubstr(fmt::format("truncated: Chunk record at byte {} claims", header_end)));
  EXPECT_THAT(error, HasSubstr("10 remain"));
}

TEST(McapReaderTest, FlippedChunkByteFailsTheChunkCrc) {
  std::string bytes = SampleBytes(McapCompression::kNone, 12);
  const std::size_t header_end = 8 + 9 + static_cast<std::size_t>(ReadLe(bytes, 9, 8));
  const std::size_t chunk_end =
      header_end + 9 + static_cast<std::size_t>(ReadLe(bytes, header_end + 1, 8));
  // The last bytes of an uncompressed chunk are the last message's data.
  bytes[chunk_end - 3] = static_cast<char>(bytes[chunk_end - 3] ^ 0x01);
  EXPECT_THAT(ErrorOf(bytes),
              HasSubstr(fmt::format("Chunk record at byte {}: CRC mismatch", header_end)));
}

TEST(McapReaderTest, RefusesWrongMagic) {
  std::string bytes = FileWith("");
  EXPECT_THAT(ErrorOf("GIF89a"), HasSubstr("does not start with the MCAP magic"));
  bytes[bytes.size() - 1] = 'x';
  EXPECT_THAT(ErrorOf(bytes), HasSubstr("closing MCAP magic"));
}

TEST(McapReaderTest, RefusesAbsurdChunkSizeWithoutAllocatingIt) {
  EXPECT_THAT(ErrorOf(FileWith(Chunk("zstd", "tiny", std::uint64_t{1} << 40, 0))),
              HasSubstr("over the 1073741824 byte limit"));
}

TEST(McapReaderTest, RefusesChunksWhoseSizeLies) {
  const std::string records = Schema(1) + Channel(2, 1) + Message(2, 50, std::string(500, 'z'));
  for (const McapCompression c : {McapCompression::kZstd, McapCompression::kLz4}) {
    const std::string stored = mcap::CompressChunkRecords(c, records);
    const std::string_view name = mcap::CompressionName(c);
    EXPECT_THAT(ErrorOf(FileWith(Chunk(name, stored, records.size() - 1, 0))),
                HasSubstr("decompresses to more than uncompressed_size"))
        << name;
    EXPECT_THAT(ErrorOf(FileWith(Chunk(name, stored, records.size() + 1, 0))),
                HasSubstr(fmt::format("decompresses to {} bytes", records.size())))
        << name;
    EXPECT_THAT(
        ErrorOf(FileWith(Chunk(name, stored.substr(0, stored.size() / 2), records.size(), 0))),
        HasSubstr("mid-frame"))
        << name;
  }
  EXPECT_THAT(ErrorOf(FileWith(Chunk("", records, records.size() + 1, 0))),
              HasSubstr("uncompressed_size says"));
}

TEST(McapReaderTest, RefusesUnknownCompression) {
  EXPECT_THAT(ErrorOf(FileWith(Chunk("bz2", "BZh9", 10, 0))),
              HasSubstr("compression 'bz2': unsupported compression"));
}

TEST(McapReaderTest, RefusesReferencesToUndefinedRecords) {
  EXPECT_THAT(ErrorOf(FileWith(Schema(1) + Channel(2, 1) + Message(3, 1, ""))),
              HasSubstr("refers to channel 3, not defined before it"));
  EXPECT_THAT(ErrorOf(FileWith(Channel(2, 4))), HasSubstr("refers to schema 4"));
  EXPECT_THAT(ErrorOf(FileWith(Schema(1) + Rec(0x03, Le(1, 2) + Str("Other") + Str("") + Str("")))),
              HasSubstr("redefines schema 1 differently"));
  EXPECT_THAT(ErrorOf(FileWith(Schema(1) + Channel(2, 1) + Channel(2, 0))),
              HasSubstr("redefines channel 2 differently"));
  // The same record again is no redefinition.
  EXPECT_EQ(ErrorOf(FileWith(Schema(1) + Schema(1) + Channel(2, 1) + Channel(2, 1))), "(no error)");
}

TEST(McapReaderTest, RefusesMisplacedRecords) {
  EXPECT_THAT(ErrorOf(FileWith(Rec(0x0B, std::string(40, '\0')))),
              HasSubstr("Statistics record at byte"));
  EXPECT_THAT(ErrorOf(FileWith(Rec(0x07, Le(1, 2) + Le(0, 4)))),
              HasSubstr("does not follow a Chunk"));
  EXPECT_THAT(ErrorOf(FileWith(Rec(0x00, ""))), HasSubstr("0x00 is not a valid opcode"));
}

TEST(McapReaderTest, MissingFileIsAnInputError) {
  TempDir dir;
  EXPECT_THROW(ReadMcapFile(dir.File("missing.mcap")), InputError);
}

}  // namespace
}  // namespace lookout::io
