#include "lookout/io/gzip_file.h"

#include <fmt/format.h>
#include <zlib.h>

#include <array>
#include <fstream>
#include <memory>
#include <string_view>

#include "lookout/core/input_error.h"
#include "lookout/io/file_bytes.h"

namespace lookout::io {
namespace {

struct GzCloser {
  void operator()(gzFile_s* file) const { gzclose_r(file); }
};

std::string ReadGzip(const std::filesystem::path& path) {
  std::unique_ptr<gzFile_s, GzCloser> file(gzopen(path.c_str(), "rb"));
  if (!file) throw InputError(path.string(), 0, "", "cannot open the file");
  // A large buffer: the logs are tens of megabytes once inflated.
  gzbuffer(file.get(), 1u << 17);
  std::string text;
  std::array<char, 1 << 16> chunk{};
  for (;;) {
    const int n = gzread(file.get(), chunk.data(), static_cast<unsigned>(chunk.size()));
    if (n < 0) break;  // the error is read below
    if (n == 0) break;
    text.append(chunk.data(), static_cast<std::size_t>(n));
  }
  int code = Z_OK;
  const char* message = gzerror(file.get(), &code);
  // Z_BUF_ERROR is zlib's "unexpected end of file": the stream stopped before its trailer.
  if (code != Z_OK) {
    throw InputError(path.string(), 0, "",
                     fmt::format("corrupt or truncated gzip stream ({})", message));
  }
  return text;
}

}  // namespace

bool HasGzipMagic(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string ReadMaybeGzippedFile(const std::filesystem::path& path) {
  std::array<char, 2> magic{};
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), 0, "", "cannot open the file");
    in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
    if (in.gcount() < 2) return ReadFileBytes(path.string());
  }
  if (HasGzipMagic(std::string_view(magic.data(), magic.size()))) return ReadGzip(path);
  return ReadFileBytes(path.string());
}

}  // namespace lookout::io
