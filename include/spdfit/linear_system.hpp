// Linear systems A x = b: classification (finite solutions and solutions at infinity), the
// minimum-norm least-squares solution from the edited SVD, and the evidence behind both.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/outcome.hpp"


namespace spdfit {

/// Options for solve().
#pragma GCC diagnostic push
// The deprecated field below must not warn in the copies the compiler writes for every user.
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
struct LinearSystemOptions {
  /// Relative singular-value cut-off: sigma_i is treated as zero when sigma_i <= rank_tolerance *
  /// sigma_max (and always when sigma_i == 0), for the singular values of A with its columns
  /// scaled to unit norm (so that the rank does not depend on the units of the unknowns; see
  /// solve()). Nothing (the default) means max(m, n) * machine epsilon, the editing rule of the
  /// lecture notes (shared/seeds/002_fe976fdf53be9def.txt, section 3.8). The same name as
  /// FitOptions::rank_tolerance; the command line spells it --threshold, Python threshold.
  std::optional<double> rank_tolerance;

  /// The old name of rank_tolerance (negative: the default), used when rank_tolerance is not set;
  /// removed in the next release.
  [[deprecated("use rank_tolerance")]] double threshold = -1.0;

  /// The reciprocal condition number below which A counts as ill-conditioned and a warning is
  /// added (notes 002, section 3.7.2: "if lambda(A) < 1e-12, A is ill-conditioned"), judged on
  /// A with its columns scaled to unit norm (1 / scaled_condition_number), as the rank is.
  double rcond_warning = 1e-12;

  /// The most unknowns (columns of A) solve() accepts. It computes the full n x n V of the SVD and
  /// returns the null space, n x (n - rank): n^2 numbers, which a wide A of a few kilobytes of text
  /// would otherwise turn into terabytes. At the default, V takes 134 MB.
  Eigen::Index max_unknowns = 4096;

  /// True when the options are usable; otherwise `error` says why.
  bool is_valid(std::string* error = nullptr) const;

  /// The cut-off used for an m x n matrix.
  double cutoff(Eigen::Index m, Eigen::Index n) const;
};
#pragma GCC diagnostic pop

/// How the notes classify A x = b by the number of equations m and unknowns n (section 3.3.2).
enum class SystemShape {
  Underdetermined,  ///< m < n
  Determined,       ///< m == n
  Overdetermined,   ///< m > n
};

/// "underdetermined", "determined", "overdetermined".
const char* to_string(SystemShape shape);

/// The classification of one right-hand side b_j.
///
/// The projective view of notes 002 section 3.3.2: A x = b_j is the homogeneous system
/// [A | -b_j] [x; w] = 0, whose solutions with w != 0 are the finite solutions x / w and whose
/// solutions with w == 0 are the points at infinity (A x = 0). Consequently
///  - the system is consistent exactly when rank [A | -b_j] == rank A (Rouche-Capelli);
///  - the finite solutions form an affine set of dimension n - rank A (0 a point, 1 a line,
///    2 a plane ...) when consistent, and none (-1) otherwise;
///  - the solutions at infinity form a projective set of dimension n - rank A - 1 (0 a
///    single point, 1 a line ...; -1 none) whether or not the system is consistent: they are the
///    directions of the null space of A. For a consistent system they are the points at
///    infinity of the finite solution set; for an inconsistent one they are all there is.
struct ColumnClassification {
  bool consistent = false;
  Eigen::Index finite_solution_dimension = -1;
  Eigen::Index at_infinity_dimension = -1;
  Eigen::Index augmented_rank = 0;  ///< numerical rank of [A | -b_j] (b_j scaled to norm ||A||_2)
  double residual_norm = 0.0;       ///< ||A x_j - b_j||_2 for the minimum-norm solution x_j
  /// ||A x_j - b_j|| / (||A||_2 ||x_j|| + ||b_j||): the normwise backward error of x_j
  /// (Rigal and Gaches); about machine epsilon when the system is consistent.
  double backward_error = 0.0;
};

/// Whether solve produced a solution. Misuse (shapes, NaN input, invalid options) throws
/// std::invalid_argument instead.
enum class SolveStatus {
  Success,
  NumericalFailure,  ///< the solution does not fit in a double; see `message`
};

/// The result of solve(A, B): everything the notes read off the SVD of A.
#pragma GCC diagnostic push
// The deprecated field below must not warn in the copies the compiler writes for every user.
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
struct LinearSystemResult {
  /// NumericalFailure only when the solution does not fit in a double (b huge against A); the
  /// classification is still filled in, the solution is empty and `message` says why.
  SolveStatus status = SolveStatus::Success;
  std::string message;

  Eigen::Index m = 0, n = 0, p = 0;  ///< A is m x n, B is m x p (p right-hand sides)
  SystemShape shape = SystemShape::Determined;

  Eigen::VectorXd singular_values;   ///< of A, descending (min(m, n) of them)
  double rank_tolerance = 0.0;       ///< the relative cut-off that was used
  /// The old name of rank_tolerance (the same value); removed in the next release.
  [[deprecated("use rank_tolerance")]] double threshold = 0.0;
  /// Number of singular values kept: decided on scaled_singular_values, those of A D with the
  /// columns of A D of about unit norm (D = diag of powers of two), not on singular_values.
  Eigen::Index rank = 0;
  Eigen::Index nullity = 0;          ///< n - rank
  double condition_number = 0.0;     ///< sigma_max / sigma_min of A (unedited); +inf when singular
  double reciprocal_condition_number = 0.0;  ///< sigma_min / sigma_max (notes 3.7.2); 0 when singular
  double effective_condition_number = 0.0;  ///< sigma_max / sigma_rank of A: of the edited A
  /// The singular values of A D, descending: A with its columns scaled by powers of two to norms
  /// in [0.5, 1). The same whatever the units of the unknowns; the rank is decided on these.
  Eigen::VectorXd scaled_singular_values;
  /// Their ratio sigma_max / sigma_min: the condition number that bounds the solution's error
  /// (van der Sluis: within sqrt(n) of the smallest over all column scalings); +inf when singular.
  double scaled_condition_number = 0.0;
  /// Steps of iterative refinement taken on the solution (full column rank only; 0 otherwise).
  int refinement_steps = 0;

  /// The classification of the set A X = B: consistent when every column is; the dimensions
  /// are per column (they depend only on rank A, so they are the same for every consistent
  /// column); finite_solution_dimension is -1 as soon as one column is inconsistent.
  bool consistent = false;
  Eigen::Index finite_solution_dimension = -1;
  Eigen::Index at_infinity_dimension = -1;
  std::vector<ColumnClassification> columns;  ///< one per right-hand side

  Eigen::MatrixXd solution;   ///< n x p: X = V_r diag(1/sigma_i) U_r^T B (notes eq. 3.21)
  double residual_norm = 0.0; ///< ||A X - B||_F
  /// n x (n - rank), orthonormal columns: A N ~= 0. Each column of null_space and range has its
  /// entry of largest magnitude positive (a singular vector's sign is otherwise arbitrary).
  Eigen::MatrixXd null_space;
  Eigen::MatrixXd range;      ///< m x rank, orthonormal columns spanning the range of A

  std::string explanation;            ///< the answer in words, in the notes' terms
  std::vector<Warning> warnings;  ///< ill-conditioning, edited singular values

  bool ok() const { return status == SolveStatus::Success; }
};
#pragma GCC diagnostic pop

/// Solves and classifies A x = b for each column of B (notes 002 sections 3.3.2 and 3.7-3.8).
///
/// The SVD A = U diag(sigma) V^T gives the rank (singular values below the options' cut-off are
/// edited to zero), the null space (columns of V for the edited sigma_i), the range (columns of
/// U for the kept ones), the condition number, and the minimum-norm least-squares solution
/// x = V diag(1/sigma_i) U^T b with 1/sigma_i set to 0 for the edited values (eq. 3.21). It is
/// the exact solution when the system is consistent and the least-squares approximation
/// otherwise. Consistency and the projective classification use the SVD of [A | -b_j] with b_j
/// scaled to the norm of A (a homogeneous coordinate can be scaled freely) and the same cut-off.
///
/// A and B are first scaled by powers of two (exactly) so that their largest entries are of order
/// one, and every result is scaled back: the answer does not depend on the units, from denormal
/// data to 1e300. The rank is decided on A D, A's columns scaled by powers of two to about unit
/// norm, so that it does not depend on the units of each unknown either (a polynomial basis
/// x^0 ... x^10 is not declared singular because its columns differ in size). At full column
/// rank the solution is computed in the scaled unknowns and refined by Bjorck's iterative
/// refinement with residuals in twice double precision: it is then as accurate as the data
/// allow, and scaling a column of A by a power of two scales the solution's entry by exactly the
/// inverse factor. When the rank is lower the minimum-norm solution, the range and the null
/// space come from the SVD of A itself, as eq. 3.21 defines them.
///
/// Preconditions: A non-empty with at most options.max_unknowns columns, B with A's number of
/// rows and at least one column, all entries finite; valid options (else std::invalid_argument).
/// A singular A is an answer, not an error; the one numerical failure is a solution beyond the
/// range of double (status NumericalFailure). Cost: O(m n min(m, n)) for the SVDs of A D and of
/// A plus O(m n^2) per column of B for the augmented matrix; memory O(n^2) for V.
LinearSystemResult solve(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                         const LinearSystemOptions& options = {});

}  // namespace spdfit
