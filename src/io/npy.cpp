// Reading .npy files (NumPy's binary format) holding a 1-D or 2-D float64 array.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

#include "npy_header.hpp"
#include "spdfit/io.hpp"
#include "text_scan.hpp"

namespace spdfit::io {

namespace {

// .npy errors have no line or column; positions, if any, are in the message.
[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw DataError(source, 0, 0, problem);
}

// Assembling the bytes explicitly makes the result independent of the host's byte order.
double decode_double(const char* bytes, bool big_endian) {
  std::uint64_t bits = 0;
  for (int k = 0; k < 8; ++k) {
    const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[k]));
    bits |= byte << (8 * (big_endian ? 7 - k : k));
  }
  double value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

}  // namespace

Eigen::MatrixXd parse_npy(std::string_view bytes, const std::string& source, const ReadOptions& options) {
  const detail::NpyHeader header = detail::parse_npy_header(bytes, source);

  const bool big_endian = header.descr == ">f8";
  if (header.structured) {
    fail(source, "structured dtypes are not supported; save a plain float64 array");
  }
  if (header.descr != "<f8" && !big_endian) {
    fail(source, "dtype " + detail::quote_token(header.descr) + " is not supported; save as float64");
  }
  const std::string shape = detail::format_shape(header.shape);
  if (header.shape.empty()) fail(source, "shape () is a single number; save a 1-D or 2-D array");
  if (header.shape.size() > 2) {
    // The shape itself only when short: a damaged header may list thousands of dimensions.
    const std::string which = header.shape.size() <= 8 ? "shape " + shape + " has " : "it has ";
    fail(source, which + std::to_string(header.shape.size()) + " dimensions; save a 1-D or 2-D array");
  }

  // Check the claimed size against the file before allocating anything, so that a damaged or
  // hostile header (shape (10**12, 10**12)) fails at once instead of exhausting memory.
  const std::uint64_t rows = header.shape[0];
  const std::uint64_t cols = header.shape.size() == 2 ? header.shape[1] : 1;
  const std::size_t data_bytes = bytes.size() - header.data_offset;
  const std::uint64_t held = data_bytes / 8;
  std::string holds = std::to_string(held);
  if (data_bytes % 8 != 0) {
    holds += " values and " + std::to_string(data_bytes % 8) +
             (data_bytes % 8 == 1 ? " stray byte" : " stray bytes");
  }
  if (rows != 0 && cols > std::numeric_limits<std::uint64_t>::max() / rows) {
    fail(source, "shape " + shape + " is impossibly large; the file holds " + holds);
  }
  const std::uint64_t count = rows * cols;
  if (count != held || data_bytes % 8 != 0) {
    fail(source, "header claims " + std::to_string(count) + " values, file holds " + holds + " (shape is " +
                     shape + ")");
  }
  if (count == 0) fail(source, "no data (shape " + shape + ")");

  // Both dimensions are at most `count`, which fits in memory, so they fit in Eigen::Index.
  const auto m = static_cast<Eigen::Index>(rows);
  const auto n = static_cast<Eigen::Index>(cols);
  Eigen::MatrixXd X(m, n);
  const char* data = bytes.data() + header.data_offset;
  if (header.fortran_order) {
    double* out = X.data();  // column-major, like Fortran order
    for (std::uint64_t k = 0; k < count; ++k) out[k] = decode_double(data + 8 * k, big_endian);
  } else {
    for (Eigen::Index i = 0; i < m; ++i) {
      for (Eigen::Index j = 0; j < n; ++j) {
        X(i, j) = decode_double(data + 8 * (i * n + j), big_endian);
      }
    }
  }

  if (!options.allow_nonfinite && !X.allFinite()) {
    // Report the first one in reading order (row by row), as the text reader would.
    for (Eigen::Index i = 0; i < m; ++i) {
      for (Eigen::Index j = 0; j < n; ++j) {
        const double x = X(i, j);
        if (std::isfinite(x)) continue;
        const std::string what = std::isnan(x) ? "NaN" : x < 0 ? "-Inf" : "Inf";
        fail(source, "entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) + ") is " + what +
                         " (rows and columns counted from 1)");
      }
    }
  }
  return X;
}

}  // namespace spdfit::io
