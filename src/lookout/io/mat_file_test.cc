#include "lookout/io/mat_file.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

// Builds MAT v5 bytes the way the format describes them, in either byte order, so the tests
// control every field. Independent of the reader: it only appends bytes.
class MatBuilder {
 public:
  explicit MatBuilder(bool big_endian = false) : big_endian_(big_endian) {
    std::string text = "MATLAB 5.0 MAT-file, test";
    text.resize(116, ' ');
    bytes_ = text + std::string(8, '\0');
    Put16(bytes_, 0x0100);
    bytes_ += big_endian ? "MI" : "IM";
  }

  template <typename T>
  void PutRaw(std::string& out, T value) const {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big_endian_) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
  }
  void Put16(std::string& out, std::uint16_t v) const { PutRaw(out, v); }
  void Put32(std::string& out, std::uint32_t v) const { PutRaw(out, v); }

  // A tagged element, padded to 8 bytes.
  std::string Element(std::uint32_t type, const std::string& data) const {
    std::string out;
    Put32(out, type);
    Put32(out, static_cast<std::uint32_t>(data.size()));
    out += data;
    out.resize((out.size() + 7) / 8 * 8, '\0');
    return out;
  }
  // The small data element format: up to 4 bytes packed beside the type.
  std::string SmallElement(std::uint32_t type, const std::string& data) const {
    std::string out;
    Put32(out, (static_cast<std::uint32_t>(data.size()) << 16) | type);
    std::string padded = data;
    padded.resize(4, '\0');
    return out + padded;
  }

  // A miMATRIX element: flags (class, complex), dims, name, then `payload` (already tagged).
  std::string Matrix(std::uint32_t mx_class, std::vector<std::int32_t> dims,
                     const std::string& name, const std::string& payload,
                     std::uint32_t extra_flags = 0) const {
    std::string flags;
    Put32(flags, mx_class | extra_flags);
    Put32(flags, 0);
    std::string dim_data;
    for (const std::int32_t d : dims) PutRaw(dim_data, d);
    std::string body =
        Element(6, flags) + Element(5, dim_data) +
        (name.size() <= 4 && !name.empty() ? SmallElement(1, name) : Element(1, name)) + payload;
    return Element(14, body);
  }

  template <typename T>
  std::string Data(std::uint32_t type, const std::vector<T>& values) const {
    std::string data;
    for (const T v : values) PutRaw(data, v);
    return Element(type, data);
  }

  static std::string Compress(const std::string& element) {
    uLongf size = compressBound(static_cast<uLong>(element.size()));
    std::string out(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(out.data()), &size,
                       reinterpret_cast<const Bytef*>(element.data()),
                       static_cast<uLong>(element.size())),
              Z_OK);
    out.resize(size);
    return out;
  }
  std::string Compressed(const std::string& element) const {
    std::string out;
    Put32(out, 15);
    const std::string z = Compress(element);
    Put32(out, static_cast<std::uint32_t>(z.size()));
    return out + z;  // not padded, as MATLAB writes it
  }

  MatBuilder& Add(const std::string& element) {
    bytes_ += element;
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  bool big_endian_;
  std::string bytes_;
};

constexpr std::uint32_t kMxCell = 1, kMxChar = 4, kMxDouble = 6, kMxInt16 = 10;
constexpr std::uint32_t kMiInt8 = 1, kMiUint8 = 2, kMiInt16 = 3, kMiSingle = 7, kMiDouble = 9,
                        kMiUint64 = 13, kMiUint16 = 4;

std::string DataPath(const std::string& file) {
  return std::string(LOOKOUT_SOURCE_DIR) + "/../shared/data/imm/" + file;
}

TEST(MatFile, ReadsADoubleMatrixInColumnMajorOrder) {
  for (const bool big : {false, true}) {
    for (const bool compressed : {false, true}) {
      SCOPED_TRACE(testing::Message() << "big_endian=" << big << " compressed=" << compressed);
      MatBuilder b(big);
      const std::string m =
          b.Matrix(kMxDouble, {2, 3}, "A", b.Data<double>(kMiDouble, {1, 2, 3, 4, 5, 6.5}));
      b.Add(compressed ? b.Compressed(m) : m);
      const MatFile file = ReadMatBytes(b.bytes(), "a.mat");
      EXPECT_EQ(file.big_endian, big);
      EXPECT_EQ(file.header_text, "MATLAB 5.0 MAT-file, test");
      const Eigen::MatrixXd& a = file.Matrix("A");
      ASSERT_EQ(a.rows(), 2);
      ASSERT_EQ(a.cols(), 3);
      EXPECT_EQ(a(0, 0), 1.0);
      EXPECT_EQ(a(1, 0), 2.0);
      EXPECT_EQ(a(0, 1), 3.0);
      EXPECT_EQ(a(1, 2), 6.5);
    }
  }
}

TEST(MatFile, ConvertsEveryStoredNumericTypeToDouble) {
  for (const bool big : {false, true}) {
    MatBuilder b(big);
    b.Add(b.Matrix(kMxDouble, {1, 2}, "i8", b.Data<std::int8_t>(kMiInt8, {-5, 7})));
    b.Add(b.Matrix(kMxDouble, {1, 2}, "u16", b.Data<std::uint16_t>(kMiUint16, {65535, 2})));
    b.Add(b.Matrix(kMxInt16, {2, 1}, "i16", b.Data<std::int16_t>(kMiInt16, {-300, 300})));
    b.Add(b.Matrix(kMxDouble, {1, 1}, "f", b.Data<float>(kMiSingle, {0.25F})));
    b.Add(b.Matrix(kMxDouble, {1, 1}, "u64",
                   b.Data<std::uint64_t>(kMiUint64, {std::uint64_t{1} << 40})));
    // One byte of data in the small element format, as MATLAB writes a uint8 scalar.
    b.Add(b.Matrix(9, {1, 1}, "k", b.SmallElement(kMiUint8, std::string(1, '\xc8'))));
    const MatFile file = ReadMatBytes(b.bytes(), "types.mat");
    EXPECT_EQ(file.Matrix("i8")(0, 1), 7.0);
    EXPECT_EQ(file.Matrix("i8")(0, 0), -5.0);
    EXPECT_EQ(file.Matrix("u16")(0, 0), 65535.0);
    EXPECT_EQ(file.Matrix("i16")(0, 0), -300.0);
    EXPECT_EQ(file.Matrix("f")(0, 0), 0.25);
    EXPECT_EQ(file.Matrix("u64")(0, 0), 1099511627776.0);
    EXPECT_EQ(file.Matrix("k")(0, 0), 200.0);
  }
}

TEST(MatFile, ReadsCellsOfMatricesIncludingEmptyOnes) {
  MatBuilder b;
  const std::string c1 = b.Matrix(kMxDouble, {2, 1}, "", b.Data<double>(kMiDouble, {1, 2}));
  const std::string c2 = b.Element(14, "");  // [] as MATLAB writes it inside a cell
  const std::string c3 = b.Matrix(kMxDouble, {2, 0}, "", b.Element(kMiDouble, ""));
  b.Add(b.Compressed(b.Matrix(kMxCell, {3, 1}, "Z", c1 + c2 + c3)));
  const MatFile file = ReadMatBytes(b.bytes(), "cells.mat");
  const auto& cells = file.Cells("Z");
  ASSERT_EQ(cells.size(), 3U);
  EXPECT_EQ(file.variables.at("Z").cell_rows, 3);
  EXPECT_EQ(file.variables.at("Z").cell_cols, 1);
  EXPECT_EQ(cells[0](1, 0), 2.0);
  EXPECT_EQ(cells[1].size(), 0);
  EXPECT_EQ(cells[2].rows(), 2);
  EXPECT_EQ(cells[2].cols(), 0);
  EXPECT_THROW(file.Matrix("Z"), InputError);
  EXPECT_THROW(file.Cells("nope"), InputError);
}

TEST(MatFile, SkipsUnsupportedArraysAndSaysWhy) {
  MatBuilder b;
  b.Add(b.Matrix(kMxChar, {1, 2}, "s", b.Data<std::uint16_t>(kMiUint16, {'h', 'i'})));
  b.Add(b.Matrix(kMxDouble, {1, 1}, "z",
                 b.Data<double>(kMiDouble, {1}) + b.Data<double>(kMiDouble, {2}), 0x0800));
  b.Add(b.Matrix(kMxDouble, {1, 1, 2}, "cube", b.Data<double>(kMiDouble, {1, 2})));
  b.Add(b.Matrix(kMxDouble, {1, 1}, "ok", b.Data<double>(kMiDouble, {3})));
  const MatFile file = ReadMatBytes(b.bytes(), "skip.mat");
  ASSERT_EQ(file.variables.size(), 1U);
  EXPECT_EQ(file.Matrix("ok")(0, 0), 3.0);
  ASSERT_EQ(file.skipped.size(), 3U);
  EXPECT_EQ(file.skipped[0], "s: char array");
  EXPECT_EQ(file.skipped[1], "z: complex array");
  EXPECT_EQ(file.skipped[2], "cube: 3 dimensions (only 2-D arrays are read)");
}

// The failing field and byte offset are part of the contract: check them, not only the type.
void ExpectRefused(const std::string& bytes, const std::string& field, const std::string& text) {
  try {
    ReadMatBytes(bytes, "bad.mat");
    ADD_FAILURE() << "accepted; expected an error on " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.mat");
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.field(), field);
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(MatFile, RefusesMalformedFilesNamingFieldAndOffset) {
  ExpectRefused("MATLAB 5.0", "header", "128-byte header");
  std::string not_mat(128, ' ');
  ExpectRefused(not_mat, "header", "at file byte 126");

  MatBuilder b;
  // Two values' worth of data for a 2 x 2 matrix.
  b.Add(b.Matrix(kMxDouble, {2, 2}, "A", b.Data<double>(kMiDouble, {1, 2})));
  ExpectRefused(b.bytes(), "A.real", "16 bytes of data for 2 x 2 values of 8 bytes");

  MatBuilder truncated;
  truncated.Add(truncated.Matrix(kMxDouble, {1, 1}, "A", truncated.Data<double>(kMiDouble, {1})));
  std::string cut = truncated.bytes();
  cut.resize(cut.size() - 8);
  ExpectRefused(cut, "", "at file byte 128: element of 56 bytes runs past the end (48 left)");

  MatBuilder corrupt;
  std::string z = corrupt.Compressed(
      corrupt.Matrix(kMxDouble, {1, 1}, "A", corrupt.Data<double>(kMiDouble, {1})));
  z[12] = static_cast<char>(z[12] ^ 0x55);
  corrupt.Add(z);
  ExpectRefused(corrupt.bytes(), "", "at file byte 128: corrupt zlib data");

  MatBuilder negative;
  negative.Add(negative.Matrix(kMxDouble, {-1, 1}, "A", negative.Data<double>(kMiDouble, {1})));
  ExpectRefused(negative.bytes(), "(variable at file byte 128).dimensions", "negative dimension");

  MatBuilder twice;
  const std::string a = twice.Matrix(kMxDouble, {1, 1}, "A", twice.Data<double>(kMiDouble, {1}));
  twice.Add(a).Add(a);
  ExpectRefused(twice.bytes(), "A", "variable appears twice");
}

TEST(MatFile, RefusesAZipBombPastTheLimit) {
  MatBuilder b;
  const std::vector<double> zeros(1 << 16, 0.0);
  b.Add(b.Compressed(b.Matrix(kMxDouble, {1 << 16, 1}, "big", b.Data<double>(kMiDouble, zeros))));
  MatReadOptions small;
  small.max_decompressed_bytes = 4096;
  EXPECT_THROW(ReadMatBytes(b.bytes(), "bomb.mat", small), InputError);
  EXPECT_EQ(ReadMatBytes(b.bytes(), "bomb.mat").Matrix("big").rows(), 1 << 16);
}

// Every truncation and every single-byte change of a small compressed file is either read or
// refused with an InputError (the fuzz target explores further; this runs in every test build,
// sanitizers included).
TEST(MatFile, EveryPrefixAndByteFlipIsReadOrRefused) {
  MatBuilder b;
  b.Add(b.Compressed(b.Matrix(kMxDouble, {2, 2}, "A", b.Data<double>(kMiDouble, {1, 2, 3, 4}))));
  b.Add(b.Matrix(kMxCell, {1, 1}, "C",
                 b.Matrix(kMxDouble, {1, 1}, "", b.Data<std::int16_t>(kMiInt16, {9}))));
  const std::string good = b.bytes();
  ASSERT_EQ(ReadMatBytes(good, "good.mat").variables.size(), 2U);
  int refused = 0;
  for (std::size_t n = 0; n < good.size(); ++n) {
    try {
      ReadMatBytes(good.substr(0, n), "prefix.mat");
    } catch (const InputError&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
  for (std::size_t i = 0; i < good.size(); ++i) {
    for (const int mask : {0x01, 0x80, 0xff}) {
      std::string bad = good;
      bad[i] = static_cast<char>(bad[i] ^ mask);
      try {
        ReadMatBytes(bad, "flip.mat");
      } catch (const InputError&) {
      }
    }
  }
}

// The real data set of the IMM evaluation (docs/imm.md): scalar K, scan intervals Ts, the GNSS
// truth Xgt (x, y, vx, vy per column), the radar scans Z (a cell of 2 x m_k matrices), the
// radar platform's state `ownship` and the scans' Unix times `time`.
TEST(MatFile, ReadsTheJoyrideDataSet) {
  const MatFile file = ReadMatFile(DataPath("joyridedata.mat"));
  EXPECT_FALSE(file.big_endian);
  EXPECT_EQ(file.variables.size(), 6U);
  EXPECT_EQ(file.Matrix("ownship").rows(), 4);
  EXPECT_EQ(file.Matrix("ownship").cols(), 200);
  const Eigen::MatrixXd& time = file.Matrix("time");
  ASSERT_EQ(time.size(), 200);
  // Ts are the differences of the scan times.
  EXPECT_NEAR(time(199) - time(0), 542.8339385986328, 1e-5);
  EXPECT_TRUE(file.skipped.empty());
  EXPECT_EQ(file.Matrix("K")(0, 0), 200.0);
  const Eigen::MatrixXd& ts = file.Matrix("Ts");
  EXPECT_EQ(ts.rows(), 199);
  EXPECT_EQ(ts.cols(), 1);
  EXPECT_NEAR(ts.sum(), 542.8339385986328, 1e-9);
  EXPECT_NEAR(ts.minCoeff(), 2.4901981353759766, 1e-12);
  const Eigen::MatrixXd& truth = file.Matrix("Xgt");
  ASSERT_EQ(truth.rows(), 4);
  ASSERT_EQ(truth.cols(), 200);
  EXPECT_DOUBLE_EQ(truth(0, 0), 7096.634382913673);
  EXPECT_DOUBLE_EQ(truth(3, 0), -2.894780404039478);
  const auto& scans = file.Cells("Z");
  ASSERT_EQ(scans.size(), 200U);
  EXPECT_EQ(scans[0].rows(), 2);
  EXPECT_EQ(scans[0].cols(), 2);
  EXPECT_DOUBLE_EQ(scans[0](0, 0), 7114.88427734375);
  EXPECT_DOUBLE_EQ(scans[0](1, 1), 4357.0830078125);
  std::size_t detections = 0;
  for (const auto& scan : scans) {
    EXPECT_EQ(scan.rows(), 2);
    EXPECT_GE(scan.cols(), 1);
    EXPECT_LE(scan.cols(), 6);
    detections += static_cast<std::size_t>(scan.cols());
  }
  EXPECT_EQ(detections, 111U + 2 * 66 + 3 * 15 + 4 * 3 + 5 * 4 + 6 * 1);
}

TEST(MatFile, ReadsTheSimulatedTask2DataSet) {
  const MatFile file = ReadMatFile(DataPath("task2data.mat"));
  EXPECT_EQ(file.Matrix("K")(0, 0), 100.0);
  EXPECT_EQ(file.Matrix("Ts")(0, 0), 2.5);
  EXPECT_EQ(file.Matrix("Xgt").rows(), 5);
  EXPECT_EQ(file.Matrix("Xgt").cols(), 100);
  EXPECT_DOUBLE_EQ(file.Matrix("Xgt")(0, 0), 6.268713089792987);
  EXPECT_EQ(file.Cells("Z").size(), 100U);
  // a(k) is the 1-based column of Z{k} that the target made, 0 when it was missed: those columns
  // lie within 7 m of the truth.
  const Eigen::MatrixXd& which = file.Matrix("a");
  ASSERT_EQ(which.size(), 100);
  const auto& scans = file.Cells("Z");
  int detected = 0;
  for (Eigen::Index k = 0; k < 100; ++k) {
    const auto column = static_cast<Eigen::Index>(which(k));
    if (column == 0) continue;
    ++detected;
    ASSERT_LE(column, scans[static_cast<std::size_t>(k)].cols());
    const Eigen::Vector2d error = scans[static_cast<std::size_t>(k)].col(column - 1) -
                                  file.Matrix("Xgt").col(k).head<2>();
    EXPECT_LT(error.norm(), 7.0) << "scan " << k;
  }
  EXPECT_GT(detected, 80);
}

TEST(MatFile, MissingFileIsAnInputError) {
  EXPECT_THROW(ReadMatFile("/nonexistent/x.mat"), InputError);
}

}  // namespace
}  // namespace lookout::io
