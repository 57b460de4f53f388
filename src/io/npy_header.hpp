// The .npy file header: magic bytes, version, and the Python dict literal that describes the
// array (see numpy.lib.format).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace spdfit::io::detail {

/// The first bytes of every .npy file.
inline constexpr std::string_view kNpyMagic = "\x93NUMPY";

/// What the header of a .npy file says.
struct NpyHeader {
  std::string descr;        ///< the dtype, e.g. "<f8"; empty for a structured dtype
  bool structured = false;  ///< a record dtype, described by a list of fields
  bool fortran_order = false;
  std::vector<std::uint64_t> shape;
  std::size_t data_offset = 0;  ///< where the array data starts
};

/// Reads the magic bytes, version (1.0, 2.0, 3.0) and header dict of `bytes`. Throws DataError
/// naming `source` when any of them is missing or malformed. Does not check the dtype or shape.
NpyHeader parse_npy_header(std::string_view bytes, const std::string& source);

/// A shape as Python prints it: "(12, 6)", "(12,)", "()".
std::string format_shape(const std::vector<std::uint64_t>& shape);

}  // namespace spdfit::io::detail
