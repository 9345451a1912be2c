#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace lookout::io {

// The bytes of a file, gunzipped when it is gzip. The format is known by its magic bytes
// (1f 8b), never by the name's extension: CARMEN logs come as .log, .clf, .log.gz and .gz
// renamed. Decompression uses zlib's gzip stream API (gzopen/gzread), which also reads files
// of several concatenated gzip members.
//
// Throws InputError naming the file when it cannot be opened or read, or when its gzip
// stream is corrupt or truncated (zlib reports a missing end or a wrong CRC only at the end,
// so a file cut short is refused as a whole, not read up to the cut).
std::string ReadMaybeGzippedFile(const std::filesystem::path& path);

// True when `bytes` starts with the gzip magic number.
bool HasGzipMagic(std::string_view bytes);

}  // namespace lookout::io
