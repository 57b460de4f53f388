// Internal dense linear-algebra helpers shared by the estimators. Every decomposition the
// library uses goes through here, so that a faster backend is swapped in at one place.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// A thin SVD A = U diag(s) V^T, s descending.
struct Svd {
  MatrixXd U, V;
  VectorXd s;
};

/// The SVD of a square or tall matrix: one-sided Jacobi (accurate small singular vectors, see
/// one_sided_jacobi.hpp) up to 64 columns, divide and conquer above.
Svd svd(const Eigen::Ref<const MatrixXd>& A, bool compute_u = true, bool compute_v = true);

/// The singular values only, descending.
VectorXd singular_values(const Eigen::Ref<const MatrixXd>& A);

/// The number of singular values above cutoff * s(0) (s descending). Zero when s(0) == 0.
Index numerical_rank(const Eigen::Ref<const VectorXd>& s, double cutoff);

/// sigma_max / sigma_min; +inf when sigma_min == 0 (including the zero matrix).
double condition_number(const Eigen::Ref<const VectorXd>& s);

/// The upper triangular factor R (cols x cols, zero-padded when rows < cols) of the
/// Householder QR of A.
MatrixXd triangular_factor(const Eigen::Ref<const MatrixXd>& A);

/// Copies the lower triangle onto the upper one, making the matrix exactly symmetric.
void make_symmetric_from_lower(MatrixXd& X);

/// (X + X^T) / 2 without overflow for entries near the double range.
MatrixXd symmetric_part(const Eigen::Ref<const MatrixXd>& X);

/// The smallest power-of-two exponent e with |x| < 2^e for every entry (nothing for a zero or
/// empty matrix), so that scaling by 2^-e is exact and leaves every entry below 1 in magnitude.
std::optional<int> scale_exponent(const Eigen::Ref<const MatrixXd>& X);

/// X * 2^e, exactly (bar overflow and underflow of the results), for any e.
MatrixXd times_power_of_two(const Eigen::Ref<const MatrixXd>& X, int e);

}  // namespace spdfit::detail
