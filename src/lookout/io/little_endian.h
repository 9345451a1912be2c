#pragma once

// A fixed-size value stored little-endian at `p` (the byte order of ROS1 bags and messages, and
// of zip archives). memcpy is the defined way to read an unaligned value; every machine Lookout
// runs on is little-endian (std::endian checked below), so no swap is needed. The caller
// checks that sizeof(T) bytes are there.

#include <bit>
#include <cstring>

namespace lookout::io {

static_assert(std::endian::native == std::endian::little,
              "the binary readers assume a little-endian machine");

template <typename T>
T LoadLittleEndian(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

}  // namespace lookout::io
