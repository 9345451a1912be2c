#pragma once

// 8-bit PNG images (grayscale and RGB) through libpng: for the grid's belief maps
// (io/grid_images.h) and `lookout run --snapshot`.
//
// Deterministic: the same image gives the same bytes (no tIME, tEXt or other ancillary chunks,
// fixed compression settings), so snapshots can be compared byte for byte on one machine.
// Atomic: files go to PATH.part, renamed to PATH when complete; a failed write leaves no PATH
// (and removes the .part).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lookout::io {

enum class PixelFormat { kGray8 = 1, kRgb8 = 3 };  // value = bytes per pixel

// Row-major pixels, row 0 at the top of the picture (as PNG stores it); RGB interleaved.
struct Image8 {
  int width = 0;
  int height = 0;
  PixelFormat format = PixelFormat::kRgb8;
  std::vector<std::uint8_t> pixels;  // width * height * BytesPerPixel(format)

  // An image of the given size filled with `value` in every channel.
  static Image8 Filled(int width, int height, PixelFormat format, std::uint8_t value = 0);
  int Channels() const { return static_cast<int>(format); }
  std::size_t Offset(int x, int y) const {  // index of channel 0 of pixel (x, y)
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)) *
           static_cast<std::size_t>(Channels());
  }
};

// The PNG file contents of `image`. Throws std::runtime_error for an image whose pixel count
// does not match its size, or an empty one (PNG cannot hold 0 x 0).
std::vector<std::uint8_t> EncodePng(const Image8& image);

// Writes `image` to `path` through path + ".part". Throws std::runtime_error naming the path.
void WritePng(const std::string& path, const Image8& image);

// Decodes an 8-bit grayscale or RGB PNG (what EncodePng writes; other kinds are rejected).
// Throws std::runtime_error naming `what` (a path or "memory").
Image8 DecodePng(std::span<const std::uint8_t> bytes, const std::string& what = "PNG data");
Image8 ReadPng(const std::string& path);

}  // namespace lookout::io
