// Rows appended to a TriangularFactor a chunk at a time, each chunk's rows written by the caller
// straight into the storage the QR factors: the streaming reader decodes a file's rows there, with
// no block-sized copy of A and B in between and no second pass over a chunk to check it or find
// its scale. TriangularFactor::append runs through the same loop, so both give the same bits.
// Internal.
#pragma once

#include <Eigen/Core>
#include <functional>

#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

class ChunkAppender {
 public:
  /// The largest magnitudes among a chunk's values of A and of B (0 when all are zero).
  struct Extent {
    double max_a = 0.0;
    double max_b = 0.0;
  };

  /// fill(first, len, rows) writes rows [first, first + len) of [A B] as they are (unscaled) into
  /// `rows` (len x (n + d): A's n columns, then B's d), throws if any is NaN or Inf, and returns
  /// their Extent.
  using Fill = std::function<Extent(Eigen::Index first, Eigen::Index len, Eigen::Ref<Eigen::MatrixXd> rows)>;

  /// Appends `count` rows to `factor`, fill()ed a chunk at a time into `scratch` (resized when too
  /// small, kept for the caller's next call) in the QR's own chunks (absorb_chunk_rows), each
  /// scaled and folded into R while it is in the cache. A chunk that raises the exponents rescales
  /// R exactly, by powers of two, so the result has the bits of all the rows at once. When fill
  /// throws, the factor is put back as it was.
  static void append(TriangularFactor& factor, Eigen::Index count, const Fill& fill, Eigen::MatrixXd* scratch);

  /// The factor whose state is given: R ((n + d) x (n + d), upper triangular, of the data scaled by
  /// 2^-exponent_a and 2^-exponent_b), the rows, and with an intercept the column means (data units)
  /// and the rows' total weight. For the robust fit's inner iterations, whose R comes from a
  /// weighted Gram matrix (robust/m_estimator.cpp); the caller vouches for R.
  static TriangularFactor from_triangle(const Eigen::MatrixXd& R, Eigen::Index n, Eigen::Index rows, int exponent_a,
                                        int exponent_b, bool intercept, const Eigen::VectorXd& means, double mass);
};

}  // namespace spdfit::detail
