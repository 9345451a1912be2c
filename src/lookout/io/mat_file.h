#pragma once

// Reads MATLAB Level 5 MAT-files (the format MATLAB writes by default up to `-v7`; not the
// HDF5-based `-v7.3`). Written by hand, as the task asked, though Debian 12 does package a
// reader: libmatio-dev (matio 1.5.23). It was not taken because it is a C API built against HDF5
// (for -v7.3, which we do not need) and the subset read here is small and fully documented in
// "MAT-File Format" (The MathWorks), chapter 1. Revisit if more of the format is ever needed.
//
// What it reads: real, 2-D numeric arrays of every numeric class (double, single, int8..int64,
// uint8..uint64, logical) stored with any numeric data type, and cell arrays whose cells are such
// arrays (one level: the radar scans of a data set, say). Every value becomes a double.
// Top-level elements may be zlib-compressed (miCOMPRESSED, as MATLAB writes by default) or not;
// both byte orders are read.
//
// What it skips (listed in MatFile::skipped with the reason, never silently): complex arrays,
// more than two dimensions, sparse, char, struct, object and function-handle arrays, nested
// cells. A file that breaks the format (bad header, a tag whose length runs past its parent, a
// data block shorter than its dimensions say, corrupt zlib data) throws lookout::InputError
// naming the file, line 0 (a binary file has no lines), the variable as the field, and the byte
// offset of the element in the problem text. Offsets inside a compressed element are counted in
// its decompressed stream and say so.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace lookout::io {

// One variable: a numeric matrix, or a cell array of numeric matrices.
struct MatVariable {
  bool is_cell = false;
  Eigen::MatrixXd matrix;  // when !is_cell
  // When is_cell: the cells in MATLAB's column-major order, cell_rows x cell_cols of them.
  std::vector<Eigen::MatrixXd> cells;
  Eigen::Index cell_rows = 0;
  Eigen::Index cell_cols = 0;
};

struct MatFile {
  std::string header_text;  // the 116-byte descriptive text, trailing blanks removed
  bool big_endian = false;
  std::map<std::string, MatVariable> variables;
  std::vector<std::string> skipped;  // "name: reason" for each variable not read

  // The numeric matrix `name`; InputError (naming `source`) when it is missing or a cell.
  const Eigen::MatrixXd& Matrix(const std::string& name) const;
  // The cells of cell array `name`; InputError when missing or not a cell.
  const std::vector<Eigen::MatrixXd>& Cells(const std::string& name) const;

  std::string source;  // the file name errors use
};

struct MatReadOptions {
  // A compressed element may inflate to at most this many bytes: zlib expands up to ~1000
  // times, so a small hostile file must not take gigabytes.
  std::size_t max_decompressed_bytes = std::size_t{256} << 20;
};

MatFile ReadMatFile(const std::string& path, const MatReadOptions& options = {});
// Same, from bytes; `source` names them in errors. Used by the fuzz target and the tests.
MatFile ReadMatBytes(std::string_view bytes, const std::string& source,
                     const MatReadOptions& options = {});

}  // namespace lookout::io
