#include "lookout/io/png_writer.h"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

namespace lookout::io {
namespace {

// libpng reports errors by longjmp. A longjmp over a C++ frame with live objects that have
// destructors is undefined, so every libpng call that may fail runs inside one of the small
// Run* functions below, whose locals are all trivially destructible, and the owning RAII
// objects live in their callers, above the setjmp.

struct PngErrorState {
  std::string message;
};

void OnPngError(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  if (state != nullptr) state->message = message != nullptr ? message : "unknown libpng error";
  png_longjmp(png, 1);
}

// Libraries never print (STYLE.md): warnings (an unknown ancillary chunk, say) are dropped.
void OnPngWarning(png_structp, png_const_charp) {}

struct ByteSink {
  std::vector<std::uint8_t>* bytes = nullptr;
};

void WriteToSink(png_structp png, png_bytep data, std::size_t length) {
  auto* sink = static_cast<ByteSink*>(png_get_io_ptr(png));
  bool failed = false;
  try {
    sink->bytes->insert(sink->bytes->end(), data, data + length);
  } catch (...) {
    failed = true;
  }
  if (failed) png_error(png, "out of memory");  // outside the handler: png_error longjmps
}

void FlushSink(png_structp) {}

struct ByteSource {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::size_t position = 0;
};

void ReadFromSource(png_structp png, png_bytep out, std::size_t length) {
  auto* source = static_cast<ByteSource*>(png_get_io_ptr(png));
  if (length > source->size - source->position) png_error(png, "truncated PNG data");
  std::copy_n(source->data + source->position, length, out);
  source->position += length;
}

int ColorType(PixelFormat format) {
  return format == PixelFormat::kGray8 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB;
}

bool RunEncode(png_structp png, png_infop info, const Image8& image, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, ColorType(image.format),
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Fixed settings rather than the library's defaults, so the bytes do not change with them.
  png_set_compression_level(png, 6);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

struct PngHeader {
  png_uint_32 width = 0;
  png_uint_32 height = 0;
  int bit_depth = 0;
  int color_type = 0;
  int interlace = 0;
};

bool RunReadHeader(png_structp png, png_infop info, PngHeader& header) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  png_get_IHDR(png, info, &header.width, &header.height, &header.bit_depth, &header.color_type,
               &header.interlace, nullptr, nullptr);
  return true;
}

bool RunReadPixels(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

std::size_t ExpectedBytes(const Image8& image) {
  return static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
         static_cast<std::size_t>(image.Channels());
}

std::vector<png_bytep> RowPointers(std::uint8_t* pixels, const Image8& image) {
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  const std::size_t stride =
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.Channels());
  for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = pixels + y * stride;
  return rows;
}

}  // namespace

Image8 Image8::Filled(int width, int height, PixelFormat format, std::uint8_t value) {
  Image8 image;
  image.width = width;
  image.height = height;
  image.format = format;
  image.pixels.assign(ExpectedBytes(image), value);
  return image;
}

std::vector<std::uint8_t> EncodePng(const Image8& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::runtime_error("PNG: cannot encode an empty image");
  }
  if (image.pixels.size() != ExpectedBytes(image)) {
    throw std::runtime_error("PNG: pixel buffer does not match the image size");
  }
  PngErrorState error;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, OnPngError, OnPngWarning);
  if (png == nullptr) throw std::runtime_error("PNG: cannot create the libpng writer");
  png_infop info = png_create_info_struct(png);
  struct Destroy {
    png_structp* png;
    png_infop* info;
    ~Destroy() { png_destroy_write_struct(png, info); }
  } destroy{&png, &info};
  if (info == nullptr) throw std::runtime_error("PNG: cannot create the libpng writer");

  std::vector<std::uint8_t> bytes;
  ByteSink sink{&bytes};
  png_set_write_fn(png, &sink, WriteToSink, FlushSink);
  // libpng only reads the rows when writing without transforms.
  std::vector<png_bytep> rows = RowPointers(const_cast<std::uint8_t*>(image.pixels.data()), image);
  if (!RunEncode(png, info, image, rows.data())) {
    throw std::runtime_error("PNG: encoding failed: " + error.message);
  }
  return bytes;
}

void WritePng(const std::string& path, const Image8& image) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = EncodePng(image);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  const std::string part = path + ".part";
  bool written = false;
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    if (out) {
      out.write(reinterpret_cast<const char*>(bytes.data()),
                static_cast<std::streamsize>(bytes.size()));
      out.close();
      written = !out.fail();
    }
  }
  std::error_code ec;
  if (!written) {
    std::filesystem::remove(part, ec);
    throw std::runtime_error(path + ": cannot write " + part);
  }
  std::filesystem::rename(part, path, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(part, ec);
    throw std::runtime_error(path + ": cannot rename " + part + ": " + reason);
  }
}

Image8 DecodePng(std::span<const std::uint8_t> bytes, const std::string& what) {
  PngErrorState error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, OnPngError, OnPngWarning);
  if (png == nullptr) throw std::runtime_error(what + ": cannot create the libpng reader");
  png_infop info = png_create_info_struct(png);
  struct Destroy {
    png_structp* png;
    png_infop* info;
    ~Destroy() { png_destroy_read_struct(png, info, nullptr); }
  } destroy{&png, &info};
  if (info == nullptr) throw std::runtime_error(what + ": cannot create the libpng reader");

  ByteSource source{bytes.data(), bytes.size(), 0};
  png_set_read_fn(png, &source, ReadFromSource);
  PngHeader header;
  if (!RunReadHeader(png, info, header)) {
    throw std::runtime_error(what + ": not a readable PNG: " + error.message);
  }
  if (header.bit_depth != 8 || header.interlace != PNG_INTERLACE_NONE ||
      (header.color_type != PNG_COLOR_TYPE_GRAY && header.color_type != PNG_COLOR_TYPE_RGB)) {
    throw std::runtime_error(what +
                             ": only 8-bit non-interlaced grayscale or RGB PNGs are supported");
  }
  // libpng caps each side at 1e6 by default; cap the area too, so a hostile header cannot
  // make us allocate terabytes (2^28 pixels: a 16384 x 16384 grid image).
  if (static_cast<std::uint64_t>(header.width) * header.height > (std::uint64_t{1} << 28)) {
    throw std::runtime_error(what + ": image too large");
  }
  Image8 image = Image8::Filled(
      static_cast<int>(header.width), static_cast<int>(header.height),
      header.color_type == PNG_COLOR_TYPE_GRAY ? PixelFormat::kGray8 : PixelFormat::kRgb8);
  std::vector<png_bytep> rows = RowPointers(image.pixels.data(), image);
  if (!RunReadPixels(png, rows.data())) {
    throw std::runtime_error(what + ": corrupt PNG: " + error.message);
  }
  return image;
}

Image8 ReadPng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(path + ": cannot read");
  return DecodePng(bytes, path);
}

}  // namespace lookout::io
