// The rows of a C-order .npy file read at their offset (pread) and decoded straight into a
// caller's matrix: any thread may read any rows, so that streaming reads a block's rows on the
// thread that factors them, into the chunks the QR takes (no block-sized buffer, no copy of the
// block in between). Internal to src/io and the streaming pipeline.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "npy_layout.hpp"

namespace spdfit::io::detail {

class NpyRows {
 public:
  /// Rows of the array `layout` describes in the open file `fd` (not owned: it must outlive this),
  /// counted from row `begin` of the array (0 but for a part of a file split among processes).
  NpyRows(int fd, const NpyLayout& layout, std::uint64_t begin, std::string path, bool allow_nonfinite);

  Eigen::Index columns() const { return static_cast<Eigen::Index>(layout_.cols); }
  const std::string& path() const { return path_; }

  /// Reads rows [first, first + count) (counted from `begin`) into `bytes` (resized as needed)
  /// and returns where they start there. Throws DataError when the file ends before them.
  const char* read_bytes(std::uint64_t first, Eigen::Index count, std::vector<double>* bytes) const;

  /// Reads rows [first, first + count) and decodes them into `out` (count x columns(), any outer
  /// stride), `bytes` a scratch buffer; returns their largest magnitude and whether all are finite.
  DecodedExtent read(std::uint64_t first, Eigen::Index count, Eigen::Ref<Eigen::MatrixXd> out,
                     std::vector<double>* bytes) const;

  /// Throws the reader's DataError for the first NaN or Inf of rows [first, first + count) in
  /// reading order (row by row), as RowReader::read would for a block of those rows; nothing when
  /// they are all finite or non-finite values are allowed (ReadOptions::allow_nonfinite).
  void check_finite(std::uint64_t first, Eigen::Index count, std::vector<double>* bytes) const;

 private:
  int fd_;
  NpyLayout layout_;
  std::uint64_t begin_;
  std::string path_;
  bool allow_nonfinite_;
};

}  // namespace spdfit::io::detail
