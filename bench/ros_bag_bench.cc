// Reading the leg_tracker ROS1 bag (../shared/data/legtracker, 31 MB, 34,729 messages in 36
// uncompressed chunks): the zip's inflation, the bag reader alone (records and chunks, every
// message visited undecoded), and the whole RosBagLog (every scan, odometry, tf and person
// message decoded by its definition and converted). Each benchmark is skipped, with a message,
// when the data set is absent.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>

#include "lookout/io/ros_bag.h"
#include "lookout/io/ros_bag_log.h"
#include "lookout/io/zip_entry.h"

namespace {

const std::string& ZipPath() {
  static const std::string path = std::string(LOOKOUT_SOURCE_DIR) +
                                  "/../shared/data/legtracker/general_tracking_moving_1.bag.zip";
  return path;
}

// The unzipped bag, or null without the data set; read once.
const std::string* BagBytes() {
  static const std::unique_ptr<std::string> bytes = []() -> std::unique_ptr<std::string> {
    if (!std::filesystem::exists(ZipPath())) return nullptr;
    return std::make_unique<std::string>(lookout::io::ReadSingleZipEntry(ZipPath()).data);
  }();
  return bytes.get();
}

bool SkipWithoutData(benchmark::State& state) {
  if (BagBytes() != nullptr) return false;
  state.SkipWithError(("no leg_tracker data set at " + ZipPath()).c_str());
  return true;
}

void BM_UnzipBag(benchmark::State& state) {
  if (SkipWithoutData(state)) return;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lookout::io::ReadSingleZipEntry(ZipPath()));
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(BagBytes()->size()));
}
BENCHMARK(BM_UnzipBag)->Unit(benchmark::kMillisecond);

void BM_VisitBagMessages(benchmark::State& state) {
  if (SkipWithoutData(state)) return;
  std::int64_t messages = 0;
  for (auto _ : state) {
    lookout::io::RosBag bag(*BagBytes(), "bench.bag");
    bag.ForEachMessage([&](const lookout::io::RosConnection&, const lookout::io::RosBagMessage& m) {
      benchmark::DoNotOptimize(m.data.data());
      ++messages;
    });
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(BagBytes()->size()));
  state.counters["messages_per_s"] =
      benchmark::Counter(static_cast<double>(messages), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VisitBagMessages)->Unit(benchmark::kMillisecond);

void BM_ReadRosBagLog(benchmark::State& state) {
  if (SkipWithoutData(state)) return;
  std::int64_t decoded = 0;
  for (auto _ : state) {
    lookout::io::RosBag bag(*BagBytes(), "bench.bag");
    const lookout::io::RosBagLog log = lookout::io::ReadRosBagLog(bag);
    decoded += static_cast<std::int64_t>(log.scans.size() + log.odometry.size() +
                                         log.people.size() + log.transforms.size());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(BagBytes()->size()));
  state.counters["records_per_s"] =
      benchmark::Counter(static_cast<double>(decoded), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReadRosBagLog)->Unit(benchmark::kMillisecond);

}  // namespace
