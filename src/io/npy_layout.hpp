// The numeric array that a .npy header describes (float64, float32, integers or booleans, all
// read as double), checked against the file's size, and decoding it a block of rows at a time (internal to src/io: parse_npy decodes all rows at
// once, the streaming RowReader a block at a time).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>

#include "npy_header.hpp"

namespace spdfit::io::detail {

struct NpyLayout {
  std::uint64_t rows = 0;
  std::uint64_t cols = 0;  ///< 1 for a 1-D array (read as a column)
  bool fortran_order = false;
  bool big_endian = false;
  char kind = 'f';             ///< 'f' float, 'i' signed integer, 'u' unsigned integer, 'b' boolean
  std::size_t item_size = 8;   ///< bytes per value: 4 or 8 for floats, 1, 2, 4 or 8 for integers, 1 for booleans
  std::size_t data_offset = 0;
};

/// Checks that the header describes a non-empty 1-D or 2-D array of float64, float32, signed or
/// unsigned integers or booleans (NumPy's <f8, <f4, <i1 ... <i8, <u1 ... <u8, |b1, either byte
/// order) whose values fill the `file_bytes` bytes after the header exactly. Throws DataError naming `source` otherwise,
/// before anything is allocated, so that a hostile shape costs nothing.
NpyLayout npy_layout(const NpyHeader& header, std::size_t file_bytes, const std::string& source);

/// Whether the values are little-endian float64 on a little-endian host: bytes that are doubles
/// as they stand.
bool is_native_double(const NpyLayout& layout);

/// Decodes rows [first, first + count) of the array whose data (after the header) start at
/// `data` into `out` (resized to count x cols). True when every value was seen to be finite on the
/// way (native doubles in C order, by rows_to_columns); false when one is NaN or Inf or when the
/// layout is not checked as it is decoded: check_npy_finite then decides, and names the value.
bool decode_npy_rows(const NpyLayout& layout, const char* data, std::uint64_t first, Eigen::Index count,
                     Eigen::MatrixXd* out);

/// What decoding a run of values saw: the largest magnitude among them (0 when all are zero), and
/// whether every one is finite (when one is not, max_abs may be anything).
struct DecodedExtent {
  double max_abs = 0.0;
  bool finite = true;
};

/// Decodes `count` rows of a C-order array of `layout`'s dtype and byte order (layout.cols values
/// a row, row after row at `from`, which needs no alignment) into `out` (count x layout.cols, any
/// outer stride: a column block of a larger matrix), in one pass that also finds the largest
/// magnitude and whether every value is finite.
DecodedExtent decode_c_order_rows(const NpyLayout& layout, const char* from, Eigen::Index count,
                                  Eigen::Ref<Eigen::MatrixXd> out);

/// Native doubles in C order (`count` rows of `cols`, row after row, at `from`, which needs no
/// alignment) into `out` (resized to count x cols, column-major), in one pass that also tells
/// whether every value is finite (false: a NaN or Inf, which check_npy_finite then names).
bool rows_to_columns(const char* from, Eigen::Index count, Eigen::Index cols, Eigen::MatrixXd* out);

/// Throws DataError naming the first NaN or Inf of `block` in reading order (row by row), with
/// row numbers counted from 1 at the array's first row, `first_row` being block's first.
void check_npy_finite(const Eigen::Ref<const Eigen::MatrixXd>& block, std::uint64_t first_row, const std::string& source);

}  // namespace spdfit::io::detail
