// Reading .npy files (NumPy's binary format) holding a 1-D or 2-D numeric array: float64 as it
// is, float32, integers and booleans converted to double (as NumPy's astype(float) does;
// integers beyond 2^53 in magnitude round to the nearest double).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

#include "npy_layout.hpp"
#include "parse.hpp"
#include "spdfit/io.hpp"
#include "text_scan.hpp"

namespace spdfit::io {

namespace {

// .npy errors have no line or column; positions, if any, are in the message.
[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw DataError(source, 0, 0, problem);
}

// One value of any supported dtype, as a double. Assembling the bytes explicitly makes the
// result independent of the host's byte order.
double decode_value(const char* bytes, char kind, std::size_t size, bool big_endian) {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < size; ++k) {
    const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[k]));
    bits |= byte << (8 * (big_endian ? size - 1 - k : k));
  }
  switch (kind) {
    case 'f':
      if (size == 4) {
        float value;
        const auto narrow = static_cast<std::uint32_t>(bits);
        std::memcpy(&value, &narrow, sizeof(value));
        return value;
      } else {
        double value;
        std::memcpy(&value, &bits, sizeof(value));
        return value;
      }
    case 'i': {
      // Sign-extend from `size` bytes.
      const unsigned shift = static_cast<unsigned>(64 - 8 * size);
      return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
    }
    case 'b':
      return bits != 0 ? 1.0 : 0.0;
    default:  // 'u'
      return static_cast<double>(bits);
  }
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace

namespace detail {

NpyLayout npy_layout(const NpyHeader& header, std::size_t file_bytes, const std::string& source) {
  NpyLayout layout;
  layout.fortran_order = header.fortran_order;
  layout.data_offset = header.data_offset;
  if (header.structured) {
    fail(source, "structured dtypes are not supported; save a plain numeric array");
  }
  // descr: a byte order ('<', '>', or '|' where it does not matter), a kind and a size in bytes.
  const std::string& d = header.descr;
  const bool known = d.size() == 3 && (d[0] == '<' || d[0] == '>' || d[0] == '|') &&
                     ((d[1] == 'f' && (d[2] == '4' || d[2] == '8')) ||
                      ((d[1] == 'i' || d[1] == 'u') && (d[2] == '1' || d[2] == '2' || d[2] == '4' || d[2] == '8')) ||
                      (d[1] == 'b' && d[2] == '1'));
  // '|' (no byte order) is what NumPy writes for one-byte types only.
  if (!known || ((d[0] == '|') != (d[2] == '1'))) {
    fail(source, "dtype " + quote_token(d) +
                     " is not supported; save as float64 (float32, integers and booleans are read too)");
  }
  layout.big_endian = d[0] == '>';
  layout.kind = d[1];
  layout.item_size = static_cast<std::size_t>(d[2] - '0');
  const std::string shape = format_shape(header.shape);
  if (header.shape.empty()) fail(source, "shape () is a single number; save a 1-D or 2-D array");
  if (header.shape.size() > 2) {
    // The shape itself only when short: a damaged header may list thousands of dimensions.
    const std::string which = header.shape.size() <= 8 ? "shape " + shape + " has " : "it has ";
    fail(source, which + std::to_string(header.shape.size()) + " dimensions; save a 1-D or 2-D array");
  }

  // Check the claimed size against the file before allocating anything, so that a damaged or
  // hostile header (shape (10**12, 10**12)) fails at once instead of exhausting memory.
  layout.rows = header.shape[0];
  layout.cols = header.shape.size() == 2 ? header.shape[1] : 1;
  const std::size_t data_bytes = file_bytes - header.data_offset;
  const std::size_t size = layout.item_size;
  const std::uint64_t held = data_bytes / size;
  std::string holds = std::to_string(held);
  if (data_bytes % size != 0) {
    holds += " values and " + std::to_string(data_bytes % size) +
             (data_bytes % size == 1 ? " stray byte" : " stray bytes");
  }
  if (layout.rows != 0 && layout.cols > std::numeric_limits<std::uint64_t>::max() / layout.rows) {
    fail(source, "shape " + shape + " is impossibly large; the file holds " + holds);
  }
  const std::uint64_t count = layout.rows * layout.cols;
  if (count != held || data_bytes % size != 0) {
    fail(source, "header claims " + std::to_string(count) + " values, file holds " + holds + " (shape is " +
                     shape + ")");
  }
  if (count == 0) fail(source, "no data (shape " + shape + ")");
  return layout;
}

bool is_native_double(const NpyLayout& layout) {
  return layout.kind == 'f' && layout.item_size == 8 && !layout.big_endian && host_is_little_endian();
}

bool decode_npy_rows(const NpyLayout& layout, const char* data, std::uint64_t first, Eigen::Index count,
                     Eigen::MatrixXd* out) {
  // Both dimensions are at most the file's value count, so they fit in Eigen::Index.
  const auto n = static_cast<Eigen::Index>(layout.cols);
  out->resize(count, n);
  if (count == 0) return true;  // past the end: an empty block has no storage for memcpy to write to
  if (!is_native_double(layout)) {
    // Other dtypes and byte orders, converted value by value.
    const std::size_t size = layout.item_size;
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = 0; i < count; ++i) {
        const std::uint64_t index = layout.fortran_order
                                        ? static_cast<std::uint64_t>(j) * layout.rows + first + static_cast<std::uint64_t>(i)
                                        : (first + static_cast<std::uint64_t>(i)) * layout.cols + static_cast<std::uint64_t>(j);
        (*out)(i, j) = decode_value(data + size * index, layout.kind, size, layout.big_endian);
      }
    }
    return false;
  }
  if (layout.fortran_order) {
    // Column j's rows are contiguous: copy each column's run of `count` rows.
    for (Eigen::Index j = 0; j < n; ++j) {
      const char* column = data + 8 * (static_cast<std::uint64_t>(j) * layout.rows + first);
      std::memcpy(out->col(j).data(), column, 8 * static_cast<std::size_t>(count));
    }
    return false;
  }
  return rows_to_columns(data + 8 * first * layout.cols, count, n, out);
}

namespace {

// Native doubles, C order: see decode_c_order_rows. Two passes over the bytes (in the cache: a
// chunk of rows at a time), each simple enough for the compiler to vectorize or pipeline: the
// largest magnitude and the finiteness over the values as they lie, then the copy into columns,
// eight rows at a time, so that each column receives a whole cache line per visit.
DecodedExtent native_rows_to_columns(const char* from, Eigen::Index count, Eigen::Index cols, double* to,
                                     Eigen::Index stride) {
  // x - x is 0 for a finite x and NaN for NaN and Inf: a sum of them is 0 exactly when all are
  // finite. Both run on pairs of doubles in four independent accumulators (GCC's vector types:
  // SSE2 on any x86-64; the compiler does not vectorize these reductions by itself).
  using Pair = double __attribute__((vector_size(16)));
  using PairBits = std::int64_t __attribute__((vector_size(16)));
  constexpr int kPairs = 4;
  const PairBits magnitude_bits = {std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::max()};
  Pair biggest[kPairs] = {};
  Pair nonfinite[kPairs] = {};
  const std::size_t values = static_cast<std::size_t>(count * cols);
  std::size_t k = 0;
  for (; k + 2 * kPairs <= values; k += 2 * kPairs) {
    for (int q = 0; q < kPairs; ++q) {
      Pair x;
      std::memcpy(&x, from + 8 * (k + 2 * static_cast<std::size_t>(q)), sizeof(x));
      const Pair magnitude = reinterpret_cast<Pair>(reinterpret_cast<PairBits>(x) & magnitude_bits);
      biggest[q] = biggest[q] > magnitude ? biggest[q] : magnitude;
      nonfinite[q] += x - x;
    }
  }
  DecodedExtent extent;
  double rest = 0.0;
  for (; k < values; ++k) {
    double x;
    std::memcpy(&x, from + 8 * k, 8);
    extent.max_abs = std::max(extent.max_abs, std::fabs(x));
    rest += x - x;
  }
  bool finite = rest == 0.0;
  for (int q = 0; q < kPairs; ++q) {
    for (int lane = 0; lane < 2; ++lane) {
      extent.max_abs = std::max(extent.max_abs, static_cast<double>(biggest[q][lane]));
      finite = finite && nonfinite[q][lane] == 0.0;
    }
  }
  extent.finite = finite;

  constexpr Eigen::Index kTile = 8;
  auto copy = [&](Eigen::Index i, Eigen::Index j) {
    std::memcpy(to + j * stride + i, from + 8 * static_cast<std::size_t>(i * cols + j), 8);
  };
  Eigen::Index i = 0;
  for (; i + kTile <= count; i += kTile) {
    for (Eigen::Index j = 0; j < cols; ++j) {
      for (Eigen::Index t = 0; t < kTile; ++t) copy(i + t, j);
    }
  }
  for (; i < count; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) copy(i, j);
  }
  return extent;
}

}  // namespace

DecodedExtent decode_c_order_rows(const NpyLayout& layout, const char* from, Eigen::Index count,
                                  Eigen::Ref<Eigen::MatrixXd> out) {
  const auto cols = static_cast<Eigen::Index>(layout.cols);
  if (is_native_double(layout)) return native_rows_to_columns(from, count, cols, out.data(), out.outerStride());
  // Other dtypes and byte orders, converted value by value.
  DecodedExtent extent;
  const std::size_t size = layout.item_size;
  for (Eigen::Index i = 0; i < count; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) {
      const double value =
          decode_value(from + size * static_cast<std::size_t>(i * cols + j), layout.kind, size, layout.big_endian);
      out(i, j) = value;
      if (!std::isfinite(value)) {
        extent.finite = false;
      } else {
        extent.max_abs = std::max(extent.max_abs, std::fabs(value));
      }
    }
  }
  return extent;
}

bool rows_to_columns(const char* from, Eigen::Index count, Eigen::Index cols, Eigen::MatrixXd* out) {
  out->resize(count, cols);
  return native_rows_to_columns(from, count, cols, out->data(), count).finite;
}

void check_npy_finite(const Eigen::Ref<const Eigen::MatrixXd>& block, std::uint64_t first_row, const std::string& source) {
  if (block.allFinite()) return;
  // Report the first one in reading order (row by row), as the text reader would.
  for (Eigen::Index i = 0; i < block.rows(); ++i) {
    for (Eigen::Index j = 0; j < block.cols(); ++j) {
      const double x = block(i, j);
      if (std::isfinite(x)) continue;
      const std::string what = std::isnan(x) ? "NaN" : x < 0 ? "-Inf" : "Inf";
      fail(source, "entry (" + std::to_string(first_row + static_cast<std::uint64_t>(i) + 1) + ", " +
                       std::to_string(j + 1) + ") is " + what + " (rows and columns counted from 1)");
    }
  }
}

}  // namespace detail

Eigen::MatrixXd parse_npy(std::string_view bytes, const std::string& source, const ReadOptions& options) {
  const detail::NpyHeader header = detail::parse_npy_header(bytes, source);
  const detail::NpyLayout layout = detail::npy_layout(header, bytes.size(), source);
  Eigen::MatrixXd X;
  const bool finite = detail::decode_npy_rows(layout, bytes.data() + layout.data_offset, 0,
                                              static_cast<Eigen::Index>(layout.rows), &X);
  if (!options.allow_nonfinite && !finite) detail::check_npy_finite(X, 0, source);
  return X;
}

}  // namespace spdfit::io
