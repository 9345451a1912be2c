#include "lookout/io/ros_bag.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "lookout/core/input_error.h"
#include "lookout/io/ros_bag_test_support.h"

namespace lookout::io {
namespace {

using testing::TestBagWriter;

struct Sent {
  std::uint32_t connection;
  RosTime time;
  std::string data;
};

// Three connections, ten messages of assorted sizes (one large enough to span lz4 blocks).
std::vector<Sent> SampleMessages() {
  std::vector<Sent> out;
  for (std::uint32_t i = 0; i < 10; ++i) {
    std::string data(i == 4 ? 200000 : 10 + i * 7, '\0');
    for (std::size_t k = 0; k < data.size(); ++k) data[k] = static_cast<char>((k * 31 + i) % 251);
    out.push_back({i % 3, RosTime{1000 + i, i * 1000}, std::move(data)});
  }
  return out;
}

std::string SampleBag(const std::string& compression, bool index,
                      std::size_t messages_per_chunk = 3) {
  TestBagWriter writer({compression, messages_per_chunk, index});
  writer.AddConnection(0, "/a", "t/A", "uint8[] data\n");
  writer.AddConnection(1, "/b", "t/B", "uint8[] data\n");
  writer.AddConnection(2, "/c", "t/C", "uint8[] data\n");
  for (const Sent& m : SampleMessages()) writer.AddMessage(m.connection, m.time, m.data);
  return writer.Finish();
}

std::vector<Sent> ReadAll(RosBag& bag, const std::set<std::uint32_t>* wanted = nullptr) {
  std::vector<Sent> out;
  bag.ForEachMessage(
      [&](const RosConnection& c, const RosBagMessage& m) {
        EXPECT_EQ(c.id, m.connection);
        out.push_back({m.connection, m.time, std::string(m.data)});
      },
      wanted);
  return out;
}

void ExpectSame(const std::vector<Sent>& read, const std::vector<Sent>& sent) {
  ASSERT_EQ(read.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(read[i].connection, sent[i].connection) << i;
    EXPECT_EQ(read[i].time, sent[i].time) << i;
    EXPECT_EQ(read[i].data, sent[i].data) << i;
  }
}

class RosBagRoundTrip : public ::testing::TestWithParam<std::tuple<std::string, bool>> {};

TEST_P(RosBagRoundTrip, MessagesConnectionsAndIndex) {
  const auto& [compression, index] = GetParam();
  RosBag bag(SampleBag(compression, index), "sample.bag");
  EXPECT_EQ(bag.stats().used_index, index);
  if (index) {
    ASSERT_EQ(bag.connections().size(), 3U);  // known before any chunk is read
    ASSERT_EQ(bag.chunk_infos().size(), 4U);
    EXPECT_EQ(bag.chunk_infos()[0].start_time, (RosTime{1000, 0}));
    EXPECT_EQ(bag.chunk_infos()[0].end_time, (RosTime{1002, 2000}));
    EXPECT_EQ(bag.chunk_infos()[3].message_counts.at(0), 1U);
  }
  ExpectSame(ReadAll(bag), SampleMessages());
  ASSERT_EQ(bag.connections().size(), 3U);
  const RosConnection& b = bag.connections().at(1);
  EXPECT_EQ(b.topic, "/b");
  EXPECT_EQ(b.type, "t/B");
  EXPECT_EQ(b.message_definition, "uint8[] data\n");
  EXPECT_EQ(b.md5sum, std::string(32, '0'));
  EXPECT_EQ(b.callerid, "/test");
  EXPECT_EQ(bag.stats().chunks_read, 4U);
  EXPECT_EQ(bag.stats().chunks_skipped, 0U);
}

INSTANTIATE_TEST_SUITE_P(Compressions, RosBagRoundTrip,
                         ::testing::Combine(::testing::Values("none", "bz2", "lz4"),
                                            ::testing::Bool()));

TEST(RosBag, TheIndexLetsUnwantedChunksGoUndecompressed) {
  // One message per chunk: chunks of /a hold no /b.
  RosBag bag(SampleBag("bz2", true, 1), "sample.bag");
  const std::set<std::uint32_t> wanted{1};
  const std::vector<Sent> read = ReadAll(bag, &wanted);
  std::vector<Sent> expected;
  for (const Sent& m : SampleMessages()) {
    if (m.connection == 1) expected.push_back(m);
  }
  ExpectSame(read, expected);
  EXPECT_EQ(bag.stats().chunks_read, 3U);
  EXPECT_EQ(bag.stats().chunks_not_needed, 7U);
}

TEST(RosBag, RefusesWhatIsNotABag) {
  try {
    RosBag bag("#ROSBAG V1.2\n", "old.bag");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "old.bag");
    EXPECT_EQ(e.line(), 1);
    EXPECT_EQ(e.field(), "magic");
  }
  std::string bag = SampleBag("none", true);
  bag[13 + 4 + 4 + 3] = 'X';  // the bag header's op value: after magic, two lengths, 'op='
  try {
    RosBag b(bag, "bad.bag");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 14);  // the 1-based byte position of the bag header record
    EXPECT_EQ(e.field(), "bag header.op");
    EXPECT_EQ(e.problem(), "is 88, not 3 (byte offset 13)");
  }
}

TEST(RosBag, CorruptedChunkIsSkippedAndTheRestRead) {
  for (const std::string compression : {"bz2", "lz4"}) {
    std::string bytes = SampleBag(compression, true);
    RosBag clean(bytes, "clean.bag");
    const std::uint64_t second_chunk = clean.chunk_infos()[1].position;
    bytes[second_chunk + 80] = static_cast<char>(bytes[second_chunk + 80] ^ 0x5a);
    RosBag bag(bytes, "flipped.bag");
    const std::vector<Sent> read = ReadAll(bag);
    std::vector<Sent> expected = SampleMessages();
    expected.erase(expected.begin() + 3, expected.begin() + 6);
    ExpectSame(read, expected);
    EXPECT_EQ(bag.stats().chunks_skipped, 1U) << compression;
    ASSERT_EQ(bag.stats().warnings.size(), 1U);
    EXPECT_NE(bag.stats().warnings[0].find(fmt::format("chunk at byte {} skipped", second_chunk)),
              std::string::npos)
        << bag.stats().warnings[0];
  }
}

TEST(RosBag, ChunkSizesAreNotTakenOnTrust) {
  // A bz2 chunk claiming 4 GiB and one claiming 100 MB more than it holds: both skipped,
  // without allocating what they claim.
  for (const std::uint32_t size : {0xffffffffU, 100000000U}) {
    const std::string records = TestBagWriter::Record(
        {{"op", "\x02"}, {"conn", TestBagWriter::U32(0)}, {"time", TestBagWriter::Time({1, 0})}},
        "abc");
    std::string compressed(1000, '\0');
    auto n = static_cast<unsigned int>(compressed.size());
    ASSERT_EQ(BZ2_bzBuffToBuffCompress(compressed.data(), &n, const_cast<char*>(records.data()),
                                       static_cast<unsigned int>(records.size()), 9, 0, 0),
              BZ_OK);
    compressed.resize(n);
    std::string bytes = SampleBag("none", false);
    bytes += TestBagWriter::Record({{"op", "\x05"}, {"compression", "bz2"},
                                    {"size", TestBagWriter::U32(size)}},
                                   compressed);
    RosBag bag(bytes, "big.bag");
    EXPECT_EQ(ReadAll(bag).size(), 10U);
    EXPECT_EQ(bag.stats().chunks_skipped, 1U);
  }
}

TEST(RosBag, TruncatedFileKeepsWhatCameBefore) {
  const std::string bytes = SampleBag("none", true);
  RosBag whole(bytes, "whole.bag");
  const std::uint64_t third_chunk = whole.chunk_infos()[2].position;
  RosBag cut(bytes.substr(0, third_chunk + 50), "cut.bag");
  EXPECT_FALSE(cut.stats().used_index);
  EXPECT_EQ(cut.stats().truncated_bytes, 50U);
  std::vector<Sent> expected = SampleMessages();
  expected.resize(6);
  ExpectSame(ReadAll(cut), expected);
}

// Every prefix and, for the smallest bag, every single-byte corruption: an InputError or a
// read that keeps going, never a crash (ASan/UBSan builds check the "never" part).
TEST(RosBag, EveryPrefixAndEveryFlippedByteIsHandled) {
  for (const std::string compression : {"none", "bz2", "lz4"}) {
    TestBagWriter writer({compression, 2, true});
    writer.AddConnection(0, "/a", "t/A", "uint8[] data\n");
    for (std::uint32_t i = 0; i < 5; ++i) writer.AddMessage(0, {i, 0}, std::string(i + 3, 'x'));
    const std::string bytes = writer.Finish();
    const auto read = [&](std::string b) {
      try {
        RosBag bag(std::move(b), "mutant.bag");
        return ReadAll(bag).size();
      } catch (const InputError&) {
        return std::size_t{0};
      }
    };
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      EXPECT_LE(read(bytes.substr(0, n)), 5U) << compression << " prefix " << n;
    }
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      std::string flipped = bytes;
      flipped[i] = static_cast<char>(flipped[i] ^ 0x81);
      EXPECT_LE(read(flipped), 5U) << compression << " flip at " << i;
    }
  }
}

}  // namespace
}  // namespace lookout::io
