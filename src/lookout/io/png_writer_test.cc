#include "lookout/io/png_writer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "lookout/io/mcap_test_support.h"

namespace lookout::io {
namespace {

using testing_support::TempDir;

Image8 Gradient(int width, int height, PixelFormat format) {
  Image8 image = Image8::Filled(width, height, format);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = static_cast<std::uint8_t>((i * 37u + i / 7u) & 0xffu);
  }
  return image;
}

void ExpectSame(const Image8& a, const Image8& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.format, b.format);
  EXPECT_EQ(a.pixels, b.pixels);
}

TEST(PngWriterTest, RgbAndGrayRoundTripThroughAFile) {
  TempDir dir;
  for (const PixelFormat format : {PixelFormat::kRgb8, PixelFormat::kGray8}) {
    const Image8 image = Gradient(13, 7, format);  // odd sizes: no row padding assumptions
    const std::string path = dir.File("image.png");
    WritePng(path, image);
    EXPECT_TRUE(std::filesystem::exists(path));
    EXPECT_FALSE(std::filesystem::exists(path + ".part"));
    ExpectSame(ReadPng(path), image);
  }
}

TEST(PngWriterTest, PixelOffsetsAreRowMajorFromTheTop) {
  Image8 image = Image8::Filled(3, 2, PixelFormat::kRgb8);
  EXPECT_EQ(image.pixels.size(), 18u);
  EXPECT_EQ(image.Offset(2, 1), 15u);
  image.pixels[image.Offset(2, 1) + 1] = 200;  // green of the bottom-right pixel
  const Image8 back = DecodePng(EncodePng(image));
  EXPECT_EQ(back.pixels[16], 200);
}

TEST(PngWriterTest, DeterministicAndWithoutAncillaryChunks) {
  const Image8 image = Gradient(40, 30, PixelFormat::kRgb8);
  const std::vector<std::uint8_t> a = EncodePng(image);
  const std::vector<std::uint8_t> b = EncodePng(image);
  EXPECT_EQ(a, b);
  // Walk the chunks: only IHDR, IDAT and IEND (no tIME, tEXt, gAMA...).
  ASSERT_GT(a.size(), 8u);
  std::size_t pos = 8;
  std::vector<std::string> types;
  while (pos + 12 <= a.size()) {
    const std::size_t length = (std::size_t{a[pos]} << 24) | (std::size_t{a[pos + 1]} << 16) |
                               (std::size_t{a[pos + 2]} << 8) | std::size_t{a[pos + 3]};
    types.emplace_back(reinterpret_cast<const char*>(&a[pos + 4]), 4);
    pos += 12 + length;
  }
  EXPECT_EQ(pos, a.size());
  ASSERT_GE(types.size(), 3u);
  EXPECT_EQ(types.front(), "IHDR");
  EXPECT_EQ(types.back(), "IEND");
  for (std::size_t i = 1; i + 1 < types.size(); ++i) EXPECT_EQ(types[i], "IDAT");
}

TEST(PngWriterTest, ErrorsNameThePathAndLeaveNoFile) {
  TempDir dir;
  const std::string missing_dir = dir.File("no/such/dir/image.png");
  try {
    WritePng(missing_dir, Image8::Filled(2, 2, PixelFormat::kGray8));
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir), std::string::npos) << e.what();
  }
  const std::string bad_size = dir.File("bad.png");
  Image8 wrong = Image8::Filled(4, 4, PixelFormat::kRgb8);
  wrong.pixels.pop_back();
  try {
    WritePng(bad_size, wrong);
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad_size), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(bad_size));
  EXPECT_FALSE(std::filesystem::exists(bad_size + ".part"));
  EXPECT_THROW(EncodePng(Image8{}), std::runtime_error);
}

TEST(PngWriterTest, ReaderRejectsGarbageAndTruncationNamingThePath) {
  TempDir dir;
  const std::string path = dir.File("garbage.png");
  {
    std::ofstream out(path, std::ios::binary);
    out << "this is not a png";
  }
  try {
    ReadPng(path);
    FAIL() << "no throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::vector<std::uint8_t> bytes = EncodePng(Gradient(20, 20, PixelFormat::kRgb8));
  bytes.resize(bytes.size() / 2);
  EXPECT_THROW(DecodePng(bytes), std::runtime_error);
  EXPECT_THROW(ReadPng(dir.File("missing.png")), std::runtime_error);
}

}  // namespace
}  // namespace lookout::io
