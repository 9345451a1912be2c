#include "lookout/io/mat_file.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "lookout/core/input_error.h"
#include "lookout/io/file_bytes.h"

namespace lookout::io {
namespace {

// Data types of the MAT v5 element tags (MAT-File Format, table 1-1).
enum MiType : std::uint32_t {
  kMiInt8 = 1,
  kMiUint8 = 2,
  kMiInt16 = 3,
  kMiUint16 = 4,
  kMiInt32 = 5,
  kMiUint32 = 6,
  kMiSingle = 7,
  kMiDouble = 9,
  kMiInt64 = 12,
  kMiUint64 = 13,
  kMiMatrix = 14,
  kMiCompressed = 15,
};

// Array classes of the array-flags subelement (table 1-3).
enum MxClass : std::uint32_t {
  kMxCell = 1,
  kMxStruct = 2,
  kMxObject = 3,
  kMxChar = 4,
  kMxSparse = 5,
  kMxDouble = 6,
  kMxUint64 = 15,
};

constexpr std::uint32_t kComplexFlag = 0x0800;

std::size_t NumericSize(std::uint32_t type) {
  switch (type) {
    case kMiInt8:
    case kMiUint8:
      return 1;
    case kMiInt16:
    case kMiUint16:
      return 2;
    case kMiInt32:
    case kMiUint32:
    case kMiSingle:
      return 4;
    case kMiDouble:
    case kMiInt64:
    case kMiUint64:
      return 8;
    default:
      return 0;
  }
}

// Where an element sits, for error messages: its offset in the file, or in the decompressed
// stream of the compressed element at `compressed_at`.
struct Place {
  std::size_t offset = 0;
  std::optional<std::size_t> compressed_at;

  std::string Describe() const {
    if (compressed_at) {
      return fmt::format(
          "byte {} of the stream inflated from the compressed element at file byte {}", offset,
          *compressed_at);
    }
    return fmt::format("file byte {}", offset);
  }
};

struct Element {
  std::uint32_t type = 0;
  std::string_view data;
  Place place;             // of the tag
  std::size_t next = 0;    // offset of the following element in the same buffer
};

class Reader {
 public:
  Reader(std::string source, bool big_endian, const MatReadOptions& options)
      : source_(std::move(source)), big_endian_(big_endian), options_(options) {}

  [[noreturn]] void Fail(const std::string& field, const Place& place,
                         const std::string& problem) const {
    throw InputError(source_, 0, field, fmt::format("at {}: {}", place.Describe(), problem));
  }

  template <typename T>
  T Load(const char* p) const {
    T value;
    std::memcpy(&value, p, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) {
      value = ByteSwap(value);
    }
    return value;
  }

  // The element whose tag starts at `offset` of `buffer`. `base` tells where `buffer` lies.
  Element ReadTag(std::string_view buffer, std::size_t offset, const Place& base,
                  const std::string& field) const {
    Place place{base.offset + offset, base.compressed_at};
    if (buffer.size() - offset < 8) {
      Fail(field, place, fmt::format("element tag needs 8 bytes, {} left", buffer.size() - offset));
    }
    const std::uint32_t first = Load<std::uint32_t>(buffer.data() + offset);
    Element element;
    element.place = place;
    // Small data element format: the byte count sits in the upper half of the first word and
    // up to four bytes of data in the second.
    if ((first >> 16) != 0) {
      element.type = first & 0xffffU;
      const std::size_t bytes = first >> 16;
      if (bytes > 4) {
        Fail(field, place, fmt::format("small data element claims {} bytes (at most 4)", bytes));
      }
      element.data = buffer.substr(offset + 4, bytes);
      element.next = offset + 8;
      return element;
    }
    element.type = first;
    const std::size_t bytes = Load<std::uint32_t>(buffer.data() + offset + 4);
    const std::size_t left = buffer.size() - offset - 8;
    if (bytes > left) {
      Fail(field, place,
           fmt::format("element of {} bytes runs past the end ({} left)", bytes, left));
    }
    element.data = buffer.substr(offset + 8, bytes);
    // Every element is padded to 8 bytes except compressed ones, which MATLAB writes back to back.
    const std::size_t padded = element.type == kMiCompressed ? bytes : (bytes + 7) / 8 * 8;
    element.next = std::min(buffer.size(), offset + 8 + padded);
    return element;
  }

  std::string Inflate(const Element& element) const {
    z_stream stream{};
    if (inflateInit(&stream) != Z_OK) {
      Fail("", element.place, "zlib could not start");
    }
    std::string out;
    out.resize(std::min<std::size_t>(options_.max_decompressed_bytes,
                                     std::max<std::size_t>(element.data.size() * 4, 64)));
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(element.data.data()));
    stream.avail_in = static_cast<uInt>(element.data.size());
    std::size_t used = 0;
    int status = Z_OK;
    while (true) {
      if (used == out.size()) {
        if (out.size() >= options_.max_decompressed_bytes) {
          inflateEnd(&stream);
          Fail("", element.place,
               fmt::format("compressed element inflates to more than {} bytes",
                           options_.max_decompressed_bytes));
        }
        out.resize(std::min(options_.max_decompressed_bytes, out.size() * 2));
      }
      const std::size_t room = std::min<std::size_t>(out.size() - used,
                                                     std::numeric_limits<uInt>::max());
      stream.next_out = reinterpret_cast<Bytef*>(out.data() + used);
      stream.avail_out = static_cast<uInt>(room);
      status = inflate(&stream, Z_NO_FLUSH);
      used += room - stream.avail_out;
      if (status == Z_STREAM_END) break;
      if (status != Z_OK && !(status == Z_BUF_ERROR && stream.avail_out == 0)) {
        inflateEnd(&stream);
        Fail("", element.place,
             fmt::format("corrupt zlib data ({})",
                         stream.msg != nullptr ? stream.msg : "truncated"));
      }
    }
    inflateEnd(&stream);
    out.resize(used);
    return out;
  }

  // Reads one miMATRIX element into `out`; returns false with `why` for a well-formed array of a
  // kind this reader skips. `allow_cell` is false inside a cell (one level only).
  bool ReadMatrix(const Element& element, bool allow_cell, std::string* name, MatVariable* out,
                  std::string* why, const std::string& field_hint) const {
    const std::string_view body = element.data;
    const Place base{element.place.offset + 8, element.place.compressed_at};
    if (body.empty()) {  // an empty array: MATLAB writes a bare tag for [] inside cells
      out->matrix.resize(0, 0);
      return true;
    }
    const Element flags = ReadTag(body, 0, base, field_hint + ".flags");
    if (flags.type != kMiUint32 || flags.data.size() != 8) {
      Fail(field_hint + ".flags", flags.place, "array flags must be 8 bytes of miUINT32");
    }
    const std::uint32_t flag_word = Load<std::uint32_t>(flags.data.data());
    const std::uint32_t mx_class = flag_word & 0xffU;

    const Element dims = ReadTag(body, flags.next, base, field_hint + ".dimensions");
    if (dims.type != kMiInt32 || dims.data.size() < 8 || dims.data.size() % 4 != 0) {
      Fail(field_hint + ".dimensions", dims.place, "dimensions must be at least two miINT32");
    }
    std::vector<std::int64_t> shape;
    for (std::size_t i = 0; i < dims.data.size(); i += 4) {
      const std::int32_t d = Load<std::int32_t>(dims.data.data() + i);
      if (d < 0) {
        Fail(field_hint + ".dimensions", dims.place, fmt::format("negative dimension {}", d));
      }
      shape.push_back(d);
    }

    const Element name_element = ReadTag(body, dims.next, base, field_hint + ".name");
    if (name_element.type != kMiInt8 && name_element.type != kMiUint8) {
      Fail(field_hint + ".name", name_element.place, "array name must be miINT8");
    }
    *name = std::string(name_element.data);
    const std::string field = name->empty() ? field_hint : *name;

    if (shape.size() > 2) {
      *why = fmt::format("{} dimensions (only 2-D arrays are read)", shape.size());
      return false;
    }
    const auto rows = static_cast<Eigen::Index>(shape[0]);
    const auto cols = static_cast<Eigen::Index>(shape[1]);
    // Both below 2^31, so the product fits in 64 bits.
    const auto count = static_cast<std::size_t>(shape[0] * shape[1]);

    if (mx_class == kMxCell) {
      if (!allow_cell) {
        *why = "a cell inside a cell (one level of cells is read)";
        return false;
      }
      out->is_cell = true;
      out->cell_rows = rows;
      out->cell_cols = cols;
      std::size_t offset = name_element.next;
      for (std::size_t i = 0; i < count; ++i) {
        const std::string cell_field = fmt::format("{}{{{}}}", field, i + 1);
        const Element cell = ReadTag(body, offset, base, cell_field);
        if (cell.type != kMiMatrix) {
          Fail(cell_field, cell.place,
               fmt::format("cell holds data type {}, not miMATRIX", cell.type));
        }
        std::string cell_name;
        MatVariable cell_value;
        if (!ReadMatrix(cell, false, &cell_name, &cell_value, why, cell_field)) {
          *why = fmt::format("cell {}: {}", i + 1, *why);
          return false;
        }
        out->cells.push_back(std::move(cell_value.matrix));
        offset = cell.next;
      }
      return true;
    }
    if (mx_class == kMxStruct || mx_class == kMxObject || mx_class == kMxChar ||
        mx_class == kMxSparse) {
      static constexpr const char* kNames[] = {"", "", "struct", "object", "char", "sparse"};
      *why = fmt::format("{} array", kNames[mx_class]);
      return false;
    }
    if (mx_class < kMxDouble || mx_class > kMxUint64) {  // double, single, then the integers
      *why = fmt::format("array class {}", mx_class);
      return false;
    }
    if ((flag_word & kComplexFlag) != 0) {
      *why = "complex array";
      return false;
    }

    const Element real = ReadTag(body, name_element.next, base, field + ".real");
    const std::size_t size = NumericSize(real.type);
    if (size == 0) {
      Fail(field + ".real", real.place, fmt::format("data type {} is not numeric", real.type));
    }
    if (real.data.size() / size != count || real.data.size() % size != 0) {
      Fail(field + ".real", real.place,
           fmt::format("{} bytes of data for {} x {} values of {} bytes", real.data.size(), rows,
                       cols, size));
    }
    out->matrix.resize(rows, cols);
    double* values = out->matrix.data();  // column-major, as MATLAB stores them
    const char* p = real.data.data();
    for (std::size_t i = 0; i < count; ++i, p += size) {
      values[i] = Decode(real.type, p);
    }
    return true;
  }

  double Decode(std::uint32_t type, const char* p) const {
    switch (type) {
      case kMiInt8: return static_cast<double>(Load<std::int8_t>(p));
      case kMiUint8: return static_cast<double>(Load<std::uint8_t>(p));
      case kMiInt16: return static_cast<double>(Load<std::int16_t>(p));
      case kMiUint16: return static_cast<double>(Load<std::uint16_t>(p));
      case kMiInt32: return static_cast<double>(Load<std::int32_t>(p));
      case kMiUint32: return static_cast<double>(Load<std::uint32_t>(p));
      case kMiSingle: return static_cast<double>(Load<float>(p));
      case kMiDouble: return Load<double>(p);
      case kMiInt64: return static_cast<double>(Load<std::int64_t>(p));
      case kMiUint64: return static_cast<double>(Load<std::uint64_t>(p));
      default: return 0.0;  // unreachable: NumericSize checked the type
    }
  }

  // One top-level element (after inflating it if compressed) into `file`.
  void ReadTopLevel(const Element& element, bool inside_compressed, MatFile* file) const {
    if (element.type == kMiCompressed) {
      if (inside_compressed) Fail("", element.place, "a compressed element inside another");
      const std::string inflated = Inflate(element);
      const Place base{0, element.place.offset};
      const Element inner = ReadTag(inflated, 0, base, "");
      if (inner.next != inflated.size() && inflated.size() - inner.next >= 8) {
        Fail("", inner.place, "compressed element holds more than one element");
      }
      ReadTopLevel(inner, true, file);  // inner.data views `inflated`, alive for this call
      return;
    }
    if (element.type != kMiMatrix) {
      file->skipped.push_back(
          fmt::format("(element at {}): data type {} at top level", element.place.Describe(),
                      element.type));
      return;
    }
    std::string name;
    MatVariable variable;
    std::string why;
    const std::string hint = fmt::format("(variable at {})", element.place.Describe());
    if (!ReadMatrix(element, true, &name, &variable, &why, hint)) {
      file->skipped.push_back(fmt::format("{}: {}", name, why));
      return;
    }
    if (name.empty()) Fail(hint, element.place, "a top-level variable has no name");
    if (file->variables.contains(name)) Fail(name, element.place, "variable appears twice");
    file->variables.emplace(std::move(name), std::move(variable));
  }

 private:
  template <typename T>
  static T ByteSwap(T value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    std::reverse(bytes, bytes + sizeof(T));
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  std::string source_;
  bool big_endian_;
  MatReadOptions options_;
};

}  // namespace

const Eigen::MatrixXd& MatFile::Matrix(const std::string& name) const {
  const auto it = variables.find(name);
  if (it == variables.end()) throw InputError(source, 0, name, "no such variable");
  if (it->second.is_cell) throw InputError(source, 0, name, "is a cell array, not a matrix");
  return it->second.matrix;
}

const std::vector<Eigen::MatrixXd>& MatFile::Cells(const std::string& name) const {
  const auto it = variables.find(name);
  if (it == variables.end()) throw InputError(source, 0, name, "no such variable");
  if (!it->second.is_cell) throw InputError(source, 0, name, "is a matrix, not a cell array");
  return it->second.cells;
}

MatFile ReadMatBytes(std::string_view bytes, const std::string& source,
                     const MatReadOptions& options) {
  constexpr std::size_t kHeaderBytes = 128;
  if (bytes.size() < kHeaderBytes) {
    throw InputError(source, 0, "header",
                     fmt::format("a MAT-file starts with a 128-byte header; the file has {} bytes",
                                 bytes.size()));
  }
  // The endian indicator is the characters 'M','I' written as a 16-bit integer: a little-endian
  // writer leaves "IM" in the file.
  const std::string_view indicator = bytes.substr(126, 2);
  bool big_endian = false;
  if (indicator == "MI") {
    big_endian = true;
  } else if (indicator != "IM") {
    throw InputError(source, 0, "header",
                     "at file byte 126: no endian indicator 'IM'/'MI' (not a MAT v5 file; a "
                     "-v7.3 file is HDF5 and not read here)");
  }
  Reader reader(source, big_endian, options);
  const auto version = reader.Load<std::uint16_t>(bytes.data() + 124);
  if (version != 0x0100) {
    throw InputError(source, 0, "header",
                     fmt::format("at file byte 124: version {:#06x}, expected 0x0100", version));
  }
  MatFile file;
  file.source = source;
  file.big_endian = big_endian;
  file.header_text = std::string(bytes.substr(0, 116));
  while (!file.header_text.empty() &&
         (file.header_text.back() == ' ' || file.header_text.back() == '\0')) {
    file.header_text.pop_back();
  }
  const std::string_view body = bytes.substr(kHeaderBytes);
  std::size_t offset = 0;
  while (offset < body.size()) {
    const Element element = reader.ReadTag(body, offset, Place{kHeaderBytes, std::nullopt}, "");
    reader.ReadTopLevel(element, false, &file);
    offset = element.next;
  }
  return file;
}

MatFile ReadMatFile(const std::string& path, const MatReadOptions& options) {
  return ReadMatBytes(ReadFileBytes(path), path, options);
}

}  // namespace lookout::io
