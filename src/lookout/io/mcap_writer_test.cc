#include "lookout/io/mcap_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "lookout/io/mcap_format.h"
#include "lookout/io/mcap_reader.h"
#include "lookout/io/mcap_test_support.h"

namespace lookout::io {
namespace {

namespace fs = std::filesystem;
using testing_support::ReadBytes;
using testing_support::ReadLe;
using testing_support::TempDir;
using testing_support::WriteSample;
using testing_support::WrittenMessage;

class McapWriterRoundTrip : public ::testing::TestWithParam<McapCompression> {};

TEST_P(McapWriterRoundTrip, ReadsBackWhatWasWritten) {
  TempDir dir;
  const std::string path = dir.File("round_trip.mcap");
  McapWriterOptions options;
  options.compression = GetParam();
  options.chunk_size_bytes = 300;
  options.profile = "x-lookout";
  McapWriter writer(path, options);
  const std::vector<WrittenMessage> written = WriteSample(writer);
  writer.Finish();

  const McapContents contents = ReadMcapFile(path);
  EXPECT_EQ(contents.profile, "x-lookout");
  EXPECT_EQ(contents.library, "lookout");
  ASSERT_EQ(contents.schemas.size(), 2u);
  EXPECT_EQ(contents.schemas.at(1).name, "lookout.Track");
  EXPECT_EQ(contents.schemas.at(1).encoding, "jsonschema");
  EXPECT_EQ(contents.schemas.at(2).data, R"({"type":"array"})");
  ASSERT_EQ(contents.channels.size(), 3u);
  const McapChannel& tracks = contents.channels.at(1);
  EXPECT_EQ(tracks.topic, "/tracks");
  EXPECT_EQ(tracks.schema_id, 1);
  EXPECT_EQ(tracks.message_encoding, "json");
  EXPECT_EQ(tracks.metadata,
            (std::map<std::string, std::string>{{"frame", "map"}, {"rate_hz", "10"}}));
  EXPECT_EQ(contents.channels.at(3).schema_id, 0);
  EXPECT_TRUE(contents.channels.at(3).metadata.empty());

  ASSERT_EQ(contents.messages.size(), written.size());
  std::map<std::uint16_t, std::uint32_t> next_sequence;
  for (std::size_t i = 0; i < written.size(); ++i) {
    const McapMessage& m = contents.messages[i];
    EXPECT_EQ(m.channel_id, written[i].channel_id) << "message " << i;
    EXPECT_EQ(m.log_time, written[i].log_time) << "message " << i;
    EXPECT_EQ(m.publish_time, written[i].publish_time) << "message " << i;
    EXPECT_EQ(m.data, written[i].data) << "message " << i;
    EXPECT_EQ(m.sequence, next_sequence[m.channel_id]++) << "message " << i;
  }
  EXPECT_GT(contents.chunk_count, 5u) << "a 300-byte chunk size should give many chunks";
}

INSTANTIATE_TEST_SUITE_P(AllCompressions, McapWriterRoundTrip,
                         ::testing::Values(McapCompression::kNone, McapCompression::kZstd,
                                           McapCompression::kLz4),
                         [](const auto& param_info) { return CompressionLabel(param_info.param); });

TEST(McapWriterTest, StatisticsCountWhatWasWritten) {
  TempDir dir;
  const std::string path = dir.File("stats.mcap");
  McapWriterOptions options;
  options.chunk_size_bytes = 500;
  McapWriter writer(path, options);
  const std::vector<WrittenMessage> written = WriteSample(writer);
  writer.Finish();

  const McapContents contents = ReadMcapFile(path);
  ASSERT_TRUE(contents.statistics.has_value());
  const McapStatistics& stats = *contents.statistics;
  EXPECT_EQ(stats.message_count, written.size());
  EXPECT_EQ(stats.schema_count, 2);
  EXPECT_EQ(stats.channel_count, 3u);
  EXPECT_EQ(stats.attachment_count, 0u);
  EXPECT_EQ(stats.metadata_count, 0u);
  EXPECT_EQ(stats.chunk_count, contents.chunk_count);
  TimeNs start = written.front().log_time;
  TimeNs end = start;
  std::map<std::uint16_t, std::uint64_t> counts;
  for (const WrittenMessage& m : written) {
    start = std::min(start, m.log_time);
    end = std::max(end, m.log_time);
    ++counts[m.channel_id];
  }
  EXPECT_EQ(stats.message_start_time, start);
  EXPECT_EQ(stats.message_end_time, end);
  EXPECT_EQ(contents.statistics_message_counts, counts);
}

TEST(McapWriterTest, EmptyRecordingIsValid) {
  TempDir dir;
  const std::string path = dir.File("empty.mcap");
  McapWriter(path).Finish();
  const McapContents contents = ReadMcapFile(path);
  EXPECT_TRUE(contents.messages.empty());
  EXPECT_EQ(contents.chunk_count, 0u);
  ASSERT_TRUE(contents.statistics.has_value());
  EXPECT_EQ(contents.statistics->message_count, 0u);
  EXPECT_EQ(contents.statistics->message_start_time, 0);
}

TEST(McapWriterTest, SameCallsGiveSameBytes) {
  TempDir dir;
  const auto write = [&](const std::string& name, bool reversed_metadata) {
    McapWriterOptions options;
    options.chunk_size_bytes = 400;
    McapWriter writer(dir.File(name), options);
    std::unordered_map<std::string, std::string> metadata;
    const std::vector<std::pair<std::string, std::string>> entries = {
        {"a", "1"}, {"b", "2"}, {"c", "3"}, {"d", "4"}, {"e", "5"}, {"f", "6"}};
    if (reversed_metadata) {
      for (auto it = entries.rbegin(); it != entries.rend(); ++it) metadata.insert(*it);
    } else {
      metadata.insert(entries.begin(), entries.end());
    }
    writer.AddChannel(0, "/meta", "json", metadata);
    WriteSample(writer);
    writer.Finish();
    return ReadBytes(dir.File(name));
  };
  const std::string first = write("first.mcap", false);
  EXPECT_FALSE(first.empty());
  EXPECT_EQ(first, write("second.mcap", false));
  EXPECT_EQ(first, write("third.mcap", true)) << "metadata order must not change the bytes";
}

TEST(McapWriterTest, WritesToPartFileAndRenamesOnFinish) {
  TempDir dir;
  const std::string path = dir.File("out.mcap");
  McapWriter writer(path);
  writer.Write(writer.AddChannel(0, "/a", "json"), 1, 1, "{}");
  EXPECT_TRUE(fs::exists(path + ".part"));
  EXPECT_FALSE(fs::exists(path));
  writer.Finish();
  EXPECT_FALSE(fs::exists(path + ".part"));
  EXPECT_TRUE(fs::exists(path));
}

TEST(McapWriterTest, UnfinishedWriterRemovesPartFile) {
  TempDir dir;
  const std::string path = dir.File("abandoned.mcap");
  {
    McapWriter writer(path);
    writer.Write(writer.AddChannel(0, "/a", "json"), 1, 1, "{}");
    ASSERT_TRUE(fs::exists(path + ".part"));
  }
  EXPECT_FALSE(fs::exists(path + ".part"));
  EXPECT_FALSE(fs::exists(path));
}

TEST(McapWriterTest, UnwritablePathThrows) {
  TempDir dir;
  EXPECT_THROW(McapWriter(dir.File("no/such/dir/out.mcap")), std::runtime_error);
}

TEST(McapWriterTest, RejectsMisuse) {
  TempDir dir;
  McapWriter writer(dir.File("misuse.mcap"));
  EXPECT_THROW(writer.AddChannel(7, "/a", "json"), std::invalid_argument);
  const std::uint16_t channel = writer.AddChannel(0, "/a", "json");
  EXPECT_THROW(writer.Write(channel + 1, 0, 0, "{}"), std::invalid_argument);
  EXPECT_THROW(writer.Write(channel, -1, 0, "{}"), std::invalid_argument);
  writer.Finish();
  EXPECT_THROW(writer.Write(channel, 0, 0, "{}"), std::logic_error);
  EXPECT_THROW(writer.Finish(), std::logic_error);
}

struct RawRecord {
  std::uint8_t opcode;
  std::size_t offset;
  std::string content;
};

// The top-level records between the magics: a literal walk, independent of McapReader.
std::vector<RawRecord> TopLevelRecords(const std::string& bytes) {
  std::vector<RawRecord> records;
  std::size_t at = mcap::kMagic.size();
  while (at + mcap::kMagic.size() < bytes.size()) {
    const auto opcode = static_cast<std::uint8_t>(bytes.at(at));
    const auto length = static_cast<std::size_t>(ReadLe(bytes, at + 1, 8));
    records.push_back({opcode, at, bytes.substr(at + 9, length)});
    at += 9 + length;
  }
  return records;
}

TEST(McapWriterTest, LayoutFollowsTheSpec) {
  TempDir dir;
  const std::string path = dir.File("layout.mcap");
  McapWriterOptions options;
  options.chunk_size_bytes = 300;
  McapWriter writer(path, options);
  WriteSample(writer);
  writer.Finish();
  const std::string bytes = ReadBytes(path);
  ASSERT_EQ(bytes.substr(0, 8), mcap::kMagic);
  ASSERT_EQ(bytes.substr(bytes.size() - 8), mcap::kMagic);

  const std::vector<RawRecord> records = TopLevelRecords(bytes);
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.front().opcode, 0x01);
  EXPECT_EQ(records.back().opcode, 0x02);

  std::vector<std::uint8_t> opcodes;
  for (const RawRecord& r : records) opcodes.push_back(r.opcode);
  std::size_t data_end = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].opcode == 0x0F) data_end = i;
    if (records[i].opcode != 0x07) continue;
    // MessageIndex entries are sorted by log time although messages were written out of order.
    const std::string& c = records[i].content;
    const auto n = static_cast<std::size_t>(ReadLe(c, 2, 4)) / 16;
    for (std::size_t k = 1; k < n; ++k) {
      EXPECT_LE(ReadLe(c, 6 + 16 * (k - 1), 8), ReadLe(c, 6 + 16 * k, 8))
          << "MessageIndex at byte " << records[i].offset;
    }
  }
  ASSERT_GT(data_end, 0u);
  // Summary: Schema, Channel, Statistics, ChunkIndex groups, then one SummaryOffset for each.
  std::vector<std::uint8_t> summary(opcodes.begin() + static_cast<std::ptrdiff_t>(data_end) + 1,
                                    opcodes.end() - 1);
  std::vector<std::uint8_t> groups;
  for (std::uint8_t op : summary) {
    if (op != 0x0E && (groups.empty() || groups.back() != op)) groups.push_back(op);
  }
  EXPECT_EQ(groups, (std::vector<std::uint8_t>{0x03, 0x04, 0x0B, 0x08}));
  EXPECT_EQ(std::count(summary.begin(), summary.end(), 0x0E), 4);

  // Footer: summary_start points just past DataEnd, and the CRC covers through its 2nd field.
  const RawRecord& footer = records.back();
  const std::uint64_t summary_start = ReadLe(footer.content, 0, 8);
  EXPECT_EQ(summary_start, records[data_end + 1].offset);
  const std::string covered = bytes.substr(summary_start, footer.offset + 9 + 16 - summary_start);
  EXPECT_EQ(ReadLe(footer.content, 16, 4), mcap::Crc32(covered));
  // DataEnd: CRC of everything before it.
  EXPECT_EQ(ReadLe(records[data_end].content, 0, 4),
            mcap::Crc32(std::string_view(bytes).substr(0, records[data_end].offset)));
}

}  // namespace
}  // namespace lookout::io
