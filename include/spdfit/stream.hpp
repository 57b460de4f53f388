// Estimating from data files larger than memory: the triangular factor of [A B] accumulated a
// block of rows at a time (TSQR), with O(n^2) state, on all cores.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "spdfit/io.hpp"
#include "spdfit/progress.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit {

/// Options for stream_factor.
struct StreamOptions {
  /// Rows per block. The result depends on it only through rounding; memory is
  /// O(block_rows n) per block in flight.
  Eigen::Index block_rows = Eigen::Index{1} << 15;
  /// Threads: 0 means one per core. A and B are read side by side and the blocks' factors are
  /// computed on up to this many threads; the result does not depend on the number.
  unsigned threads = 0;
  io::ReadOptions read;
  /// Told the fraction of A's file read, after each block (text: bytes; .npy: rows).
  ProgressCallback progress;
  /// fit_files' bootstrap with too few rows for the streaming (Poisson) scheme resamples the rows
  /// in memory when A and B take at most this many bytes as doubles, and refuses beyond it.
  std::uint64_t bootstrap_memory_bytes = std::uint64_t{256} << 20;
};

/// The triangular factor of [A B] for A and B in the files `a_path` and `b_path` (the formats
/// of io::read_table; A m x n, B m x d, m >= n), read a block of rows at a time: each block's factor
/// is computed on its own, and the factors are merged in the order of the blocks (the TSQR
/// merge of TriangularFactor), so the numerically careful path of the in-memory estimators is
/// kept (no Gram matrices) and memory stays O(threads * block_rows * (n + d) + (n + d)^2) for any m.
/// Then `fit(reduce(factor), method)` gives the estimate, equal to the in-memory one to
/// rounding.
///
/// Throws io::DataError (naming the file, line and column) on bad data, when A and B differ in
/// their numbers of rows, or when m < n. Throws std::invalid_argument when
/// block_rows < 1. Cost O(m n^2) flops, spread over the threads. When `warnings` is given it
/// receives the readers' warnings (io::Table::warnings: a first column of row labels dropped).
TriangularFactor stream_factor(const std::string& a_path, const std::string& b_path,
                               const StreamOptions& options = {}, std::vector<Warning>* warnings = nullptr);

}  // namespace spdfit
