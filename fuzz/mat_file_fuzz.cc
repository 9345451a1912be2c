// Fuzz target for the MAT v5 reader: any bytes in, a MatFile or an InputError out. Any other
// exception (std::bad_alloc from a size taken on trust included), a crash, a hang or a sanitizer
// report is a bug in the reader or in how it drives zlib.
//
// Seeds: the two real MAT-files of shared/data/imm (zlib-compressed elements, cell arrays,
// small data elements), read in place; the smoke test names that folder.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lookout/core/input_error.h"
#include "lookout/io/mat_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  lookout::io::MatReadOptions options;
  options.max_decompressed_bytes = std::size_t{16} << 20;  // stay far below libFuzzer's RSS limit
  try {
    lookout::io::ReadMatBytes(bytes, "fuzz.mat", options);
  } catch (const lookout::InputError&) {
    // The one way a bad file may be refused.
  }
  return 0;
}
