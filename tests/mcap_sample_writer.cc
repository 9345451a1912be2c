// Writes small MCAP files with known contents for the reference-reader check
// (tests/node/check_sample.sh) and the fuzz seed corpus (fuzz/corpus/mcap/):
//   OUT_DIR/sample-zstd.mcap, sample-lz4.mcap, sample-none.mcap
// each with 2 schemas, 3 channels and 40 + 25 + 10 = 75 messages on /tracks, /detections and
// /status, some written out of log-time order, in chunks of ~1 KiB.
//
// Usage: lookout_mcap_sample OUT_DIR

#include <cstdio>
#include <exception>
#include <string>

#include <fmt/format.h>

#include "lookout/io/mcap_writer.h"

namespace {

using lookout::TimeNs;
using lookout::io::McapCompression;
using lookout::io::McapWriter;
using lookout::io::McapWriterOptions;

void WriteSample(const std::string& path, McapCompression compression) {
  McapWriterOptions options;
  options.compression = compression;
  options.chunk_size_bytes = 1024;
  options.profile = "x-lookout";
  McapWriter writer(path, options);
  const std::uint16_t track = writer.AddSchema(
      "lookout.Track", "jsonschema", R"({"type":"object","properties":{"id":{"type":"integer"}}})");
  const std::uint16_t detection =
      writer.AddSchema("lookout.Detection", "jsonschema",
                       R"({"type":"object","properties":{"r":{"type":"number"}}})");
  const std::uint16_t tracks = writer.AddChannel(track, "/tracks", "json", {{"frame_id", "map"}});
  const std::uint16_t detections = writer.AddChannel(detection, "/detections", "json",
                                                     {{"frame_id", "ego"}, {"sensor", "lidar"}});
  const std::uint16_t status = writer.AddChannel(track, "/status", "json");

  constexpr TimeNs kPeriod = 100'000'000;  // 10 Hz
  for (int i = 0; i < 40; ++i) {
    // Every fifth track message arrives late, stamped before the one written just before it.
    const TimeNs t = i * kPeriod - (i % 5 == 4 ? 3 * kPeriod / 2 : 0) + kPeriod;
    writer.Write(tracks, t, t, fmt::format(R"({{"id":{},"x":{:.1f}}})", i % 4, 0.5 * i));
    if (i < 25) writer.Write(detections, t + 1000, t + 1000, fmt::format(R"({{"r":{}}})", 10 + i));
    if (i % 4 == 0) writer.Write(status, t + 2000, t + 2000, R"({"ok":true})");
  }
  writer.Finish();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fputs("usage: lookout_mcap_sample OUT_DIR\n", stderr);
    return 2;
  }
  const std::string dir = argv[1];
  try {
    WriteSample(dir + "/sample-zstd.mcap", McapCompression::kZstd);
    WriteSample(dir + "/sample-lz4.mcap", McapCompression::kLz4);
    WriteSample(dir + "/sample-none.mcap", McapCompression::kNone);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lookout_mcap_sample: %s\n", e.what());
    return 1;
  }
  return 0;
}
