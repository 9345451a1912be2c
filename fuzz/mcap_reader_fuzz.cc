// Fuzz target for the MCAP reader: any bytes in, McapContents or an InputError out. Any other
// exception (std::bad_alloc from a size taken on trust included), a crash, a hang or a sanitizer
// report is a bug in the reader or in how it drives zstd/lz4.
//
// Seeds: fuzz/corpus/mcap/ holds the three files tests/mcap_sample_writer.cc writes (zstd, lz4
// and uncompressed chunks).

#include <cstddef>
#include <cstdint>
#include <string>

#include "lookout/core/input_error.h"
#include "lookout/io/mcap_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    lookout::io::ReadMcapBytes(bytes, "fuzz.mcap");
  } catch (const lookout::InputError&) {
    // The one way a bad file may be refused.
  }
  return 0;
}
