#include "lookout/io/base64.h"

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

namespace lookout::io {
namespace {

std::string Encode(std::string_view text) {
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  return Base64Encode(bytes);
}

TEST(Base64Test, Rfc4648TestVectors) {
  EXPECT_EQ(Encode(""), "");
  EXPECT_EQ(Encode("f"), "Zg==");
  EXPECT_EQ(Encode("fo"), "Zm8=");
  EXPECT_EQ(Encode("foo"), "Zm9v");
  EXPECT_EQ(Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Encode("foobar"), "Zm9vYmFy");
}

TEST(Base64Test, HighBytes) {
  const std::vector<std::uint8_t> bytes = {0xff, 0xfe, 0x00, 0x80};
  EXPECT_EQ(Base64Encode(bytes), "//4AgA==");
}

}  // namespace
}  // namespace lookout::io
