// The triangular factor of the Householder QR of the data [A B]: everything every
// estimator needs, without forming the Gram matrices A^T A or B^T B.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>
#include <string_view>

namespace spdfit {

namespace detail {
class ChunkAppender;  // appends rows written straight into the QR's chunks (src/factor/chunk_appender.hpp)
}

/// R, the (n + d) x (n + d) upper triangular factor of the Householder QR of [A B] (A m x n,
/// B m x d; d = n for the square X of every method, d != n for the n x d X of ls and tls),
///
///     [A B] = Q R,   R = [R11 R12; 0 R22],   R11 n x n, R12 n x d, R22 d x d,
///
/// accumulated from the data in one piece or chunk by chunk. R carries every estimator's
/// input: A^T A = R11^T R11, A^T B = R11^T R12, ||A X - B||_F^2 = ||R11 X - R12||_F^2 +
/// ||R22||_F^2, and the singular values and right singular vectors of [A B] are those of R.
/// Two factors of disjoint row sets merge into the factor of their union (TSQR), which is
/// the basis of streaming and multithreading.
///
/// To keep every estimate unchanged under scaling of the data by any factor between 1e-300 and
/// 1e300, A and B are stored scaled by powers of two (exact): R is the factor of
/// [A 2^-exponent_a(), B 2^-exponent_b()], with the exponents chosen so that every scaled
/// entry has magnitude below 1. When m < n + d the bottom rows of R are zero.
///
/// Cost: O(m (n + d)^2) for m rows; memory O((n + d)^2) beyond the chunk being added.
class TriangularFactor {
 public:
  /// An empty factor for data A and B with n columns each (no rows yet). Throws
  /// std::invalid_argument when n < 1.
  explicit TriangularFactor(Eigen::Index n);
  /// An empty factor for A with n columns and B with d columns. Throws std::invalid_argument
  /// when n < 1 or d < 1.
  TriangularFactor(Eigen::Index n, Eigen::Index d);

  /// With `intercept`, an empty factor of [1 A B] (a column of ones first): for the model
  /// A X + 1 c^T ~= B with constant offsets in the columns (FitOptions::offsets, Offsets::Estimate).
  /// The QR of [1 A B] is R1 = [sqrt(m), sqrt(m) mu^T; 0, Rc], mu the column means of [A B] and Rc
  /// the factor of the rows centred by them; the factor keeps Rc as R() (what every estimator
  /// reads: the data with their offsets removed) and mu as means(). Rows are added a chunk at a
  /// time, each centred by its own mean (two passes, so that an offset 1e8 times the spread costs
  /// no accuracy) and joined to the rest by the row sqrt(m k / (m + k)) (mu - mu_chunk) (the
  /// between-chunk part), never by sums of squares: streaming, merging and resampling stay as
  /// accurate as for the plain factor. Throws std::invalid_argument when n < 1 or d < 1.
  TriangularFactor(Eigen::Index n, Eigen::Index d, bool intercept);

  /// The factor of the data A (m x n) and B (m x d), finite. Throws std::invalid_argument when
  /// the row counts differ, n < 1, d < 1, or an entry is NaN or Inf.
  static TriangularFactor from_data(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                    const Eigen::Ref<const Eigen::MatrixXd>& B);
  /// The same, of [1 A B] when `intercept` (see the constructor).
  static TriangularFactor from_data(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                    const Eigen::Ref<const Eigen::MatrixXd>& B, bool intercept);

  /// Adds the rows of A (k x n) and B (k x d), finite. Throws std::invalid_argument as
  /// from_data does, or when the column counts are not the factor's. Cost O((k + n + d) (n + d)^2).
  void append(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

  /// Makes this the factor of the union of both row sets. Throws std::invalid_argument when
  /// the column counts differ. Cost O((n + d)^3).
  void merge(const TriangularFactor& other);

  /// Adds the rows of A and B, row i counted counts[i] times (frequency weights: R^T R gains
  /// sum_i counts[i] z_i z_i^T for the rows z_i of [A B], and rows() grows by the counts' sum), as
  /// a bootstrap resample needs without copies of repeated rows. Rows with count 0 are skipped.
  /// Throws std::invalid_argument as append does, or when counts.size() != A.rows(). Cost
  /// O((k + n) n^2), k the rows with a nonzero count.
  void append(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
              const std::vector<std::uint32_t>& counts);
  /// Adds the rows of A and B with real weights w_i >= 0 (a weighted least-squares criterion, as a
  /// robust fit's reweighting needs): R^T R gains sum_i w_i z_i z_i^T (with an intercept, about the
  /// weighted means), and rows() grows by the number of rows with w_i > 0. Throws
  /// std::invalid_argument as append does, or when weights.size() != A.rows() or a weight is
  /// negative or not finite. Cost O((k + n) n^2), k the rows with w_i > 0.
  void append(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
              const Eigen::Ref<const Eigen::VectorXd>& weights);
  /// Makes this the factor of its rows and the rows of others[k], each counted counts[k] times
  /// (its R scaled by sqrt(counts[k])), in one re-triangularization; count 0 leaves a factor
  /// out. Merging with count 1 is merge(other) to rounding. Throws std::invalid_argument when
  /// the sizes of others and counts differ or a column count differs. Cost O((k + 1) n^3), k the
  /// factors with a nonzero count.
  void merge(const std::vector<const TriangularFactor*>& others, const std::vector<std::uint32_t>& counts);
  /// The factor of the union of both row sets, leaving a and b unchanged (a.merge(b) on a
  /// copy of a). Throws std::invalid_argument when the column counts differ. Cost O(n^3).
  static TriangularFactor merged(const TriangularFactor& a, const TriangularFactor& b);

  /// The factor's whole state as bytes, to send to another process (MPI) or to store (pickling):
  /// the 8-byte magic "spdfitR\0", a little-endian uint32 layout version, int64 n, in layouts 2
  /// and 3 int64 d, then uint64 rows, for A then B one byte (1 when the block's exponent is set, 0
  /// while its data were all zero) and an int32 exponent, in layout 3 the rows' total weight (the
  /// rows but for weighted ones, append with weights) and the n + d column means as
  /// little-endian IEEE doubles, then the upper triangle of R column by column as little-endian
  /// IEEE doubles. A factor with d = n is written in layout 1 (no d), as before non-square
  /// factors existed; one with d != n in layout 2; one with an intercept in layout 3.
  /// deserialize(serialize()) is the same factor, bit for bit. Cost O((n + d)^2).
  std::string serialize() const;

  /// The factor serialize() wrote (layout 1, 2 or 3). Throws std::invalid_argument, saying what is
  /// wrong, for bytes that are not such a factor: a wrong magic or version, a size that does not
  /// match n and d, n < 1, d < 1, an exponent flag other than 0 or 1, an exponent outside the
  /// range of double, a NaN or Inf entry, or rows of R beyond the rows accumulated (m < n + d)
  /// that are not zero. Cost O((n + d)^2).
  static TriangularFactor deserialize(std::string_view bytes);

  /// The factor of [A D_a, B D_b] (D = diag(scale)): R's columns multiplied by the factors (n for
  /// A's, d for B's; each finite and > 0, else std::invalid_argument), the stored exponents moved
  /// by the largest factor's power of two. For data logged in other units (FitOptions::scale_a,
  /// scale_b) after the last append: rows appended later are taken in the new units. O((n + d)^2).
  void scale_columns(const Eigen::VectorXd& scale_a, const Eigen::VectorXd& scale_b);

  Eigen::Index n() const { return n_; }  ///< A's columns: X has n rows
  Eigen::Index d() const { return d_; }  ///< B's columns: X has d columns (d = n: X square)
  Eigen::Index rows() const { return rows_; }  ///< m, the number of rows accumulated
  /// Whether this is the factor of [1 A B] (the constructor with `intercept`): R() is then of the
  /// centred rows, whose m rows carry m - 1 degrees of freedom.
  bool intercept() const { return intercept_; }
  /// With an intercept, the column means of A (the first n) and B (the last d) in the data's
  /// units; empty otherwise and before any row.
  const Eigen::VectorXd& means() const { return means_; }
  /// A is stored as A 2^-exponent_a() (0 while A has been all zero); likewise B.
  int exponent_a() const { return exponent_a_.value_or(0); }
  int exponent_b() const { return exponent_b_.value_or(0); }

  /// The (n + d) x (n + d) upper triangular factor of the scaled data.
  const Eigen::MatrixXd& R() const { return R_; }
  auto R11() const { return R_.topLeftCorner(n_, n_); }
  auto R12() const { return R_.topRightCorner(n_, d_); }
  auto R22() const { return R_.bottomRightCorner(d_, d_); }

 private:
  friend class detail::ChunkAppender;

  // Raises the stored exponents to at least (ea, eb), rescaling R exactly.
  void raise_exponents(std::optional<int> ea, std::optional<int> eb);
  // Re-triangularizes [R; rows] (the rows, already scaled, are overwritten).
  void absorb(Eigen::Ref<Eigen::MatrixXd> scaled_rows);
  // Scales rows of [A B] by the stored exponents (in place), absorbs them, and counts `count` rows.
  void absorb_rows(Eigen::Ref<Eigen::MatrixXd> rows, Eigen::Index count);
  // With an intercept: rows (unscaled), each weighted by weights[i] (null: 1), whose weights sum
  // to `count`, centred by their weighted mean, scaled, absorbed with the between-chunk row, the
  // means and the mass updated, and `row_count` rows counted.
  void absorb_centred(Eigen::Ref<Eigen::MatrixXd> rows, const std::vector<double>* weights, double count,
                      Eigen::Index row_count);

  Eigen::Index n_ = 0;
  Eigen::Index d_ = 0;
  Eigen::Index rows_ = 0;
  std::optional<int> exponent_a_;
  std::optional<int> exponent_b_;
  Eigen::MatrixXd R_;
  bool intercept_ = false;
  Eigen::VectorXd means_;  // with an intercept: the column means of [A B], in the data's units
  double mass_ = 0.0;      // with an intercept: the rows' total weight (their count, unweighted)
};

}  // namespace spdfit
