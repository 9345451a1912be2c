// Fuzz target for the MOTChallenge reader: any bytes in, rows or an InputError out. Any other
// exception, a crash or a sanitizer report is a bug in the reader.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lookout/core/input_error.h"
#include "lookout/io/mot_challenge.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    lookout::io::ParseMotChallenge(text, "fuzz.txt");
  } catch (const lookout::InputError&) {
    // The one way a bad file may be refused.
  }
  return 0;
}
