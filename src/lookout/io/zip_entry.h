#pragma once

// Reads the one file inside a .zip archive, such as a data set shipped as `log.bag.zip`, into
// memory, so that tests, benchmarks and `lookout replay` read it without an unpacking step.
//
// Written by hand over zlib (inflate of the raw deflate stream) because no Debian 12 C++
// library reads zip archives without pulling in far more (libzip, minizip are C APIs of their
// own); this covers only what a one-file archive needs. Read: the end-of-central-directory
// record, the one central-directory entry, its local header, and its data stored (method 0) or
// deflated (method 8), checked against the archive's CRC-32 and sizes. Refused with an
// InputError (field `zip`): several entries, ZIP64, encryption, other methods, any mismatch.
// Memory grows with the bytes really inflated, never past the size the archive declares.

#include <string>
#include <string_view>

namespace lookout::io {

struct ZipEntry {
  std::string name;
  std::string data;
};

// `zip` holds the archive's bytes; `source` names it in errors.
ZipEntry ExtractSingleZipEntry(std::string_view zip, const std::string& source);

// Reads the archive at `path` and extracts its single entry.
ZipEntry ReadSingleZipEntry(const std::string& path);

}  // namespace lookout::io
