#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace lookout::io {

// Standard base64 (RFC 4648, section 4, with padding): how JSON carries the bytes of a
// foxglove.Grid. Four lines of table lookups do not justify a dependency.
std::string Base64Encode(std::span<const std::uint8_t> bytes);

}  // namespace lookout::io
