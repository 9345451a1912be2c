#include "lookout/io/zip_entry.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

template <typename T>
std::string Raw(T v) {
  std::string s(sizeof(T), '\0');
  std::memcpy(s.data(), &v, sizeof(T));
  return s;
}

std::string RawDeflate(const std::string& data) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, static_cast<uLong>(data.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// A one-entry archive laid out as APPNOTE.TXT says (local header, data, central directory,
// end record), written here so that the reader is tested against the format, not itself.
std::string MakeZip(const std::string& name, const std::string& data, bool deflate,
                    std::uint16_t entries = 1) {
  const std::string stored = deflate ? RawDeflate(data) : data;
  const auto crc = static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
  const std::uint16_t method = deflate ? 8 : 0;
  const auto common = Raw<std::uint16_t>(20) + Raw<std::uint16_t>(0) + Raw(method) +
                      Raw<std::uint32_t>(0) + Raw(crc) +
                      Raw(static_cast<std::uint32_t>(stored.size())) +
                      Raw(static_cast<std::uint32_t>(data.size())) +
                      Raw(static_cast<std::uint16_t>(name.size())) + Raw<std::uint16_t>(0);
  std::string zip = Raw<std::uint32_t>(0x04034b50) + common + name + stored;
  const auto directory = static_cast<std::uint32_t>(zip.size());
  const std::string central = Raw<std::uint32_t>(0x02014b50) + Raw<std::uint16_t>(20) + common +
                              Raw<std::uint16_t>(0) + Raw<std::uint16_t>(0) +
                              Raw<std::uint16_t>(0) + Raw<std::uint32_t>(0) +
                              Raw<std::uint32_t>(0) + name;
  zip += central;
  zip += Raw<std::uint32_t>(0x06054b50) + Raw<std::uint16_t>(0) + Raw<std::uint16_t>(0) +
         Raw(entries) + Raw(entries) + Raw(static_cast<std::uint32_t>(central.size())) +
         Raw(directory) + Raw<std::uint16_t>(0);
  return zip;
}

std::string SampleData() {
  std::string data;
  for (int i = 0; i < 50000; ++i) data += static_cast<char>("ROSBAG"[i % 6] + (i / 1000) % 3);
  return data;
}

TEST(ZipEntry, StoredAndDeflated) {
  for (const bool deflate : {false, true}) {
    const ZipEntry entry =
        ExtractSingleZipEntry(MakeZip("log.bag", SampleData(), deflate), "t.zip");
    EXPECT_EQ(entry.name, "log.bag");
    EXPECT_EQ(entry.data, SampleData());
  }
}

TEST(ZipEntry, RefusesMismatchesAndOtherArchives) {
  std::string zip = MakeZip("log.bag", SampleData(), true);
  const auto expect_refused = [](const std::string& bytes, const std::string& why) {
    try {
      ExtractSingleZipEntry(bytes, "t.zip");
      ADD_FAILURE() << "accepted: " << why;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "zip") << why;
      EXPECT_EQ(e.file(), "t.zip") << why;
    }
  };
  std::string bad_crc = zip;
  const std::size_t crc_at = zip.find("PK\x01\x02", 0, 4) + 16;  // the central directory's CRC
  bad_crc[crc_at] = static_cast<char>(bad_crc[crc_at] ^ 1);
  expect_refused(bad_crc, "CRC");
  expect_refused(MakeZip("a", "x", false, 2), "two entries");
  expect_refused("not a zip at all, just some text of some length", "no end record");
  // Every prefix: the end record or the data goes missing.
  for (std::size_t n = 0; n < zip.size(); n += 7) expect_refused(zip.substr(0, n), "prefix");
}

TEST(ZipEntry, TheLegTrackerBag) {
  const std::string path = std::string(LOOKOUT_SOURCE_DIR) +
                           "/../shared/data/legtracker/general_tracking_moving_1.bag.zip";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no data at " << path;
  const ZipEntry entry = ReadSingleZipEntry(path);
  EXPECT_EQ(entry.name, "general_tracking_moving_1.bag");
  EXPECT_EQ(entry.data.size(), 31259309U);
  EXPECT_EQ(entry.data.substr(0, 13), "#ROSBAG V2.0\n");
}

}  // namespace
}  // namespace lookout::io
