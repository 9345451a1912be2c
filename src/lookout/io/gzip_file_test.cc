#include "lookout/io/gzip_file.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

namespace fs = std::filesystem;

class GzipFileTest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("lookout_gzip_test_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path WritePlain(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  // Each string of `members` becomes one gzip member, written with zlib's own gzip writer.
  fs::path WriteGzip(const std::string& name, const std::vector<std::string>& members) {
    const fs::path path = dir_ / name;
    for (std::size_t i = 0; i < members.size(); ++i) {
      gzFile file = gzopen(path.c_str(), i == 0 ? "wb" : "ab");
      EXPECT_NE(file, nullptr);
      EXPECT_EQ(gzwrite(file, members[i].data(), static_cast<unsigned>(members[i].size())),
                static_cast<int>(members[i].size()));
      EXPECT_EQ(gzclose(file), Z_OK);
    }
    return path;
  }

  fs::path dir_;
};

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  std::string bytes(static_cast<std::size_t>(in.tellg()), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return bytes;
}

std::string SomeText() {
  std::string text;
  for (int i = 0; i < 20000; ++i) text += "ODOM " + std::to_string(i) + " 0 0 0 0 0 1.5 h 1.5\n";
  return text;
}

TEST_F(GzipFileTest, PlainFileIsReadAsItIs) {
  const std::string text = "PARAM a b\nODOM 1 2 3\n";
  EXPECT_EQ(ReadMaybeGzippedFile(WritePlain("plain.log", text)), text);
}

TEST_F(GzipFileTest, GzipIsKnownByItsMagicBytesNotItsName) {
  const std::string text = SomeText();
  EXPECT_EQ(ReadMaybeGzippedFile(WriteGzip("log.clf", {text})), text);
  // A plain file named .gz stays plain.
  EXPECT_EQ(ReadMaybeGzippedFile(WritePlain("plain.log.gz", "ODOM\n")), "ODOM\n");
}

TEST_F(GzipFileTest, ConcatenatedMembersAreOneStream) {
  EXPECT_EQ(ReadMaybeGzippedFile(WriteGzip("two.gz", {"first\n", "second\n"})), "first\nsecond\n");
}

TEST_F(GzipFileTest, EmptyAndOneByteFilesArePlain) {
  EXPECT_EQ(ReadMaybeGzippedFile(WritePlain("empty.log", "")), "");
  EXPECT_EQ(ReadMaybeGzippedFile(WritePlain("one.log", "\x1f")), "\x1f");
}

TEST_F(GzipFileTest, TruncatedGzipIsRefusedNamingTheFile) {
  const fs::path whole = WriteGzip("whole.gz", {SomeText()});
  const std::string bytes = Bytes(whole);
  ASSERT_GT(bytes.size(), 100u);
  // Cut inside the deflate data, and just before the 8-byte trailer (CRC and length).
  for (const std::size_t keep : {bytes.size() / 2, bytes.size() - 4, std::size_t{2}}) {
    const fs::path cut = WritePlain("cut.gz", bytes.substr(0, keep));
    try {
      ReadMaybeGzippedFile(cut);
      ADD_FAILURE() << "a gzip cut to " << keep << " of " << bytes.size() << " bytes was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), cut.string());
      EXPECT_NE(e.problem().find("truncated"), std::string::npos) << e.what();
    }
  }
}

TEST_F(GzipFileTest, CorruptCrcIsRefused) {
  const fs::path whole = WriteGzip("whole.gz", {SomeText()});
  std::string bytes = Bytes(whole);
  bytes[bytes.size() - 8] = static_cast<char>(bytes[bytes.size() - 8] ^ 0x5a);  // the CRC-32
  EXPECT_THROW(ReadMaybeGzippedFile(WritePlain("crc.gz", bytes)), InputError);
}

TEST_F(GzipFileTest, MissingFileIsAnInputError) {
  EXPECT_THROW(ReadMaybeGzippedFile(dir_ / "no-such.log"), InputError);
}

}  // namespace
}  // namespace lookout::io
