// Fuzz target for the scenario loader: any bytes in, a Scenario or an InputError out. Any other
// exception, a crash or a sanitizer report is a bug in the loader (or in yaml-cpp beneath it,
// which the loader must then guard against).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "lookout/core/input_error.h"
#include "lookout/io/scenario_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // libFuzzer hands bytes; the loader reads text. Same bytes, no copy.
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    lookout::io::LoadScenarioText(text, "fuzz.yaml");
  } catch (const lookout::InputError&) {
    // The one way a bad file may be refused.
  }
  return 0;
}
