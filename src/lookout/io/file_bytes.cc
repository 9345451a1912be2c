#include "lookout/io/file_bytes.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "lookout/core/input_error.h"

namespace lookout::io {

std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path, 0, "", fmt::format("cannot open: {}", std::strerror(errno)));
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path, 0, "", "cannot read: not a regular file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in) throw InputError(path, 0, "", fmt::format("cannot read: {}", std::strerror(errno)));
  return bytes;
}

}  // namespace lookout::io
