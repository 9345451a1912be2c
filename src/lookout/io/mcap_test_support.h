#pragma once

// Helpers shared by the MCAP writer and reader tests. Test-only: included by *_test.cc files.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "lookout/io/mcap_writer.h"

namespace lookout::io {

inline std::string CompressionLabel(McapCompression compression) {
  switch (compression) {
    case McapCompression::kNone:
      return "None";
    case McapCompression::kZstd:
      return "Zstd";
    case McapCompression::kLz4:
      return "Lz4";
  }
  return "Unknown";
}

// Names parameterized test cases readably; found by argument-dependent lookup, hence here.
inline void PrintTo(McapCompression compression, std::ostream* os) {
  *os << CompressionLabel(compression);
}

}  // namespace lookout::io

namespace lookout::io::testing_support {

// A directory of its own for each test (ctest runs tests in parallel processes), removed after.
class TempDir {
 public:
  TempDir() {
    std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(test.begin(), test.end(), '/', '_');  // parameterized names hold a slash
    path_ = std::filesystem::temp_directory_path() /
            fmt::format("lookout-mcap-{}-{}-{}", test, getpid(), counter_++);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string File(const std::string& name) const { return (path_ / name).string(); }

 private:
  static inline int counter_ = 0;
  std::filesystem::path path_;
};

inline std::string ReadBytes(const std::string& path) {
  std::string bytes(std::filesystem::file_size(path), '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return bytes;
}

// The little-endian integer of `width` bytes at `at`.
inline std::uint64_t ReadLe(std::string_view bytes, std::size_t at, std::size_t width) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < width; ++i) {
    value |= std::uint64_t{static_cast<std::uint8_t>(bytes.at(at + i))} << (8 * i);
  }
  return value;
}

struct WrittenMessage {
  std::uint16_t channel_id;
  TimeNs log_time;
  TimeNs publish_time;
  std::string data;
};

// Writes 2 schemas, 3 channels (one schemaless, two with metadata) and `count` messages whose
// log times go back and forth; returns the messages in the order written.
inline std::vector<WrittenMessage> WriteSample(McapWriter& writer, int count = 60) {
  const std::uint16_t track =
      writer.AddSchema("lookout.Track", "jsonschema", R"({"type":"object"})");
  const std::uint16_t scan = writer.AddSchema("lookout.Scan", "jsonschema", R"({"type":"array"})");
  const std::uint16_t tracks =
      writer.AddChannel(track, "/tracks", "json", {{"frame", "map"}, {"rate_hz", "10"}});
  const std::uint16_t lidar = writer.AddChannel(scan, "/lidar", "json", {{"frame", "ego"}});
  const std::uint16_t log = writer.AddChannel(0, "/log", "json");
  std::vector<WrittenMessage> written;
  for (int i = 0; i < count; ++i) {
    // Every third message is stamped 50 ms before the one written just before it.
    const TimeNs t = TimeNs{i} * 20'000'000 - (i % 3 == 2 ? 50'000'000 : 0) + 100'000'000;
    const std::uint16_t channel = i % 3 == 0 ? tracks : (i % 3 == 1 ? lidar : log);
    WrittenMessage m{
        channel, t, t + 1'000,
        fmt::format(R"({{"i":{},"pad":"{}"}})", i, std::string(static_cast<std::size_t>(i), 'x'))};
    writer.Write(m.channel_id, m.log_time, m.publish_time, m.data);
    written.push_back(std::move(m));
  }
  return written;
}

}  // namespace lookout::io::testing_support
