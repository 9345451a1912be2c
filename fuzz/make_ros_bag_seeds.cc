// Writes the seed bags of lookout_fuzz_ros_bag into the folder given (the fuzz build runs it):
// the tests' small log with none, bz2 and lz4 chunks, without an index, and with a second scan
// topic (ros_bag_test_support.h). Made at build time so that no binary seed is kept in the
// repository.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "lookout/io/ros_bag_test_support.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_ros_bag_seeds DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  for (const auto& [name, bytes] : lookout::io::testing::FuzzSeedBags()) {
    std::ofstream out(dir / name, std::ios::binary);
    out << bytes;
    if (!out) {
      std::cerr << "make_ros_bag_seeds: cannot write " << (dir / name) << "\n";
      return 1;
    }
  }
  return 0;
}
