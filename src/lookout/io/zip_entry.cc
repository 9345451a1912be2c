#include "lookout/io/zip_entry.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "lookout/core/input_error.h"
#include "lookout/io/file_bytes.h"
#include "lookout/io/little_endian.h"

namespace lookout::io {
namespace {

// Signatures and fixed sizes of PKWARE's APPNOTE.TXT, section 4.3.
constexpr std::uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr std::uint32_t kCentralHeaderSignature = 0x02014b50;
constexpr std::uint32_t kEndOfCentralDirectorySignature = 0x06054b50;
constexpr std::size_t kLocalHeaderSize = 30;
constexpr std::size_t kCentralHeaderSize = 46;
constexpr std::size_t kEndOfCentralDirectorySize = 22;
constexpr std::size_t kMaxCommentSize = 0xffff;
constexpr std::uint16_t kMethodStored = 0;
constexpr std::uint16_t kMethodDeflated = 8;
constexpr std::uint16_t kFlagEncrypted = 0x0001;

class ZipBytes {
 public:
  ZipBytes(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  [[noreturn]] void Fail(std::size_t offset, const std::string& problem) const {
    throw InputError(source_, 0, "zip", fmt::format("{} (byte offset {})", problem, offset));
  }

  template <typename T>
  T Load(std::size_t offset) const {
    if (offset > bytes_.size() || bytes_.size() - offset < sizeof(T)) {
      Fail(offset, "the archive ends inside a header");
    }
    return LoadLittleEndian<T>(bytes_.data() + offset);
  }

  std::string_view Slice(std::size_t offset, std::size_t size) const {
    if (offset > bytes_.size() || bytes_.size() - offset < size) {
      Fail(offset, fmt::format("the archive ends inside a {}-byte field", size));
    }
    return bytes_.substr(offset, size);
  }

  std::size_t size() const { return bytes_.size(); }

 private:
  std::string_view bytes_;
  const std::string& source_;
};

std::string Inflate(const ZipBytes& zip, std::size_t offset, std::string_view compressed,
                    std::uint32_t declared_size) {
  z_stream stream{};
  // Negative window bits: a raw deflate stream, without the zlib wrapper zip does not use.
  if (inflateInit2(&stream, -MAX_WBITS) != Z_OK) zip.Fail(offset, "zlib cannot start inflating");
  std::string out;
  // Grow with the real output so that a lying size field costs nothing.
  out.resize(
      std::min<std::size_t>(declared_size, std::max<std::size_t>(1 << 16, 4 * compressed.size())));
  std::size_t used = 0;
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  int status = Z_OK;
  while (status != Z_STREAM_END) {
    if (used == out.size()) {
      if (out.size() >= declared_size) break;
      out.resize(std::min<std::size_t>(declared_size, 2 * out.size() + 1));
    }
    const std::size_t room =
        std::min<std::size_t>(out.size() - used, std::numeric_limits<uInt>::max());
    stream.next_out = reinterpret_cast<Bytef*>(out.data() + used);
    stream.avail_out = static_cast<uInt>(room);
    status = inflate(&stream, Z_NO_FLUSH);
    used += room - stream.avail_out;
    if (status != Z_OK && status != Z_STREAM_END) {
      const std::string problem = status == Z_BUF_ERROR ? "the deflate stream is cut short"
                                  : stream.msg != nullptr ? stream.msg
                                                          : "the deflate stream is corrupt";
      inflateEnd(&stream);
      zip.Fail(offset, problem);
    }
  }
  inflateEnd(&stream);
  if (status != Z_STREAM_END || used != declared_size) {
    zip.Fail(offset, fmt::format("the entry inflates to {}{} bytes, the archive says {}", used,
                                 status != Z_STREAM_END ? " or more" : "", declared_size));
  }
  out.resize(used);
  return out;
}

}  // namespace

ZipEntry ExtractSingleZipEntry(std::string_view bytes, const std::string& source) {
  const ZipBytes zip(bytes, source);
  if (bytes.size() < kEndOfCentralDirectorySize) zip.Fail(0, "too short to be a zip archive");
  // The end record is last, followed only by a comment of up to 64 KiB: search backwards.
  std::size_t end = bytes.size() - kEndOfCentralDirectorySize;
  const std::size_t lowest = end > kMaxCommentSize ? end - kMaxCommentSize : 0;
  while (zip.Load<std::uint32_t>(end) != kEndOfCentralDirectorySignature) {
    if (end == lowest) zip.Fail(0, "no end-of-central-directory record: not a zip archive");
    --end;
  }
  const auto entries = zip.Load<std::uint16_t>(end + 10);
  const auto directory_offset = zip.Load<std::uint32_t>(end + 16);
  if (directory_offset == 0xffffffff || entries == 0xffff) {
    zip.Fail(end, "ZIP64 archives are not read");
  }
  if (entries != 1) zip.Fail(end, fmt::format("the archive holds {} entries, not one", entries));

  const std::size_t central = directory_offset;
  if (zip.Load<std::uint32_t>(central) != kCentralHeaderSignature) {
    zip.Fail(central, "no central-directory header where the end record points");
  }
  const auto flags = zip.Load<std::uint16_t>(central + 8);
  const auto method = zip.Load<std::uint16_t>(central + 10);
  const auto crc = zip.Load<std::uint32_t>(central + 16);
  const auto compressed_size = zip.Load<std::uint32_t>(central + 20);
  const auto size = zip.Load<std::uint32_t>(central + 24);
  const auto name_length = zip.Load<std::uint16_t>(central + 28);
  const auto local = std::size_t{zip.Load<std::uint32_t>(central + 42)};
  ZipEntry entry;
  entry.name = std::string(zip.Slice(central + kCentralHeaderSize, name_length));
  if ((flags & kFlagEncrypted) != 0) zip.Fail(central, "encrypted entries are not read");
  if (compressed_size == 0xffffffff || size == 0xffffffff) {
    zip.Fail(central, "ZIP64 entries are not read");
  }
  if (method != kMethodStored && method != kMethodDeflated) {
    zip.Fail(central,
             fmt::format("compression method {} (only stored and deflate are read)", method));
  }

  if (zip.Load<std::uint32_t>(local) != kLocalHeaderSignature) {
    zip.Fail(local, "no local header where the central directory points");
  }
  const std::size_t data_offset = local + kLocalHeaderSize + zip.Load<std::uint16_t>(local + 26) +
                                  zip.Load<std::uint16_t>(local + 28);
  const std::string_view compressed = zip.Slice(data_offset, compressed_size);
  if (method == kMethodStored) {
    if (compressed_size != size) zip.Fail(central, "a stored entry whose two sizes differ");
    entry.data = std::string(compressed);
  } else {
    entry.data = Inflate(zip, data_offset, compressed, size);
  }
  const uLong actual_crc =
      crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(entry.data.data()),
            static_cast<uInt>(entry.data.size()));
  if (actual_crc != crc) {
    zip.Fail(data_offset, fmt::format("CRC-32 of the entry is {:08x}, the archive says {:08x}",
                                      actual_crc, crc));
  }
  return entry;
}

ZipEntry ReadSingleZipEntry(const std::string& path) {
  return ExtractSingleZipEntry(ReadFileBytes(path), path);
}

}  // namespace lookout::io
