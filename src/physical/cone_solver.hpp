// Internal: the one optimizer of physically consistent identification, shared by the hexapod's
// physical fit (hexapod/physical.cpp), the payload from a force/torque sensor (payload/) and
// `physical regress` (physical/regress.cpp): min f(theta) over the cone of cone.hpp (every body's
// pseudo-inertia P_k >= 0, the nonnegative scalars >= 0), for a smooth criterion f given with its
// gradient and Hessian. A primal barrier path (Newton steps on f + mu (-sum log det P_k - sum log
// s_j), mu decreased geometrically to rounding level) with face solves between its stages (f over
// P_k = L_k L_k^T of the ranks the iterate points to, a Burer-Monteiro factorization, which ends
// the path at a KKT point with quadratic convergence), Newton's method without constraints, and
// the KKT numbers of a result.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "physical/cone.hpp"

namespace spdfit::physical::detail {

/// Newton's method, as the barrier stages and the face solve run it: sufficient decrease of the
/// backtracking line search (Armijo) and the smallest step tried; the squared decrement (f is
/// normalized to about 1: steps of relative size about 1e-13) at which the last stage stops; the
/// rounding error of a computed criterion or barrier value in units of eps times its size, and how
/// many steps in a row may predict a decrease below it before the minimizer counts as found to
/// working accuracy.
inline constexpr double kArmijo = 1e-4;
inline constexpr double kMinStep = 1e-12;
inline constexpr double kFinalDecrement = 1e-26;
inline constexpr double kRoundingMultiple = 64.0;
inline constexpr int kRoundingSteps = 2;
/// An eigenvalue of P_k (or a nonnegative scalar) below this fraction of P_k's largest is taken to
/// leave the face a face solve works on.
inline constexpr double kActiveGuess = 1e-3;
/// A face solve's result is a KKT point when the multipliers of its active constraints are >=
/// -kDualTolerance (dimensionless, as ConeCertificate::dual_min_eig): rounding is ~1e-14 there, a
/// wrong face gives O(1e-3) and more.
inline constexpr double kDualTolerance = 1e-9;

/// The criterion's value (normalized by the caller to about 1 at the start, so that the
/// tolerances above are relative), gradient (order >= 1) and Hessian (order 2) in theta.
struct Evaluation {
  double f = 0.0;
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
};

/// A smooth criterion of theta. evaluate() returns false where it is not defined (a weight that
/// is not positive definite, a log-determinant outside its cone). The Hessian may be an
/// approximation that is positive semidefinite (Gauss-Newton): Newton's method then converges
/// linearly instead of quadratically, to the same point.
class Criterion {
 public:
  virtual ~Criterion() = default;
  virtual bool evaluate(const Eigen::VectorXd& theta, int order, Evaluation& out) const = 0;
  /// The order at which Newton's line search evaluates the full step's trial point: 0, the value
  /// alone; 2 for a criterion that keeps its last evaluation (payload's EivCriterion), so that an
  /// accepted point's derivatives, which the next step needs, come from the pass over the data
  /// that gave its value. Shorter steps are evaluated by their value.
  virtual int trial_order() const { return 0; }
};

/// How a minimization ended.
struct SolveResult {
  Eigen::VectorXd theta;
  double f = 0.0;          ///< the criterion at theta
  int iterations = 0;      ///< Newton steps
  bool converged = false;  ///< the last stage's stopping rule held
  std::string message;     ///< why not, when not converged
};

/// The first-order optimality (KKT) conditions of theta for min f over the cone; the multipliers
/// are the gradient's parts Z_k = df/dP_k, lambda_j = df/ds_j (and df/du = 0 for the free
/// parameters). Dimensionless as f is, times ||theta|| where a size is needed: stationarity is the
/// norm of the gradient along the face of the cone theta lies on (zero at a KKT point; ||theta||
/// times it), dual_min_eig the smallest eigenvalue of the Z_k and entry of lambda (>= 0 at a KKT
/// point; ||theta|| times it), primal_min_eig the smallest eigenvalue of the P_k and entry of s
/// (theta's units), complementarity sum_k <P_k, Z_k> + s . lambda (zero at a KKT point).
struct ConeCertificate {
  double stationarity = 0.0;
  double primal_min_eig = 0.0;
  double dual_min_eig = 0.0;
  double complementarity = 0.0;
};

/// True when theta is strictly inside the cone: each P_k's eigenvalues above 1e-13 of its largest,
/// and each nonnegative scalar above 1e-13 of the largest eigenvalue of all P_k (of the largest
/// scalar when there are no bodies).
bool strictly_feasible(const ConeLayout& layout, const Eigen::VectorXd& theta);

/// theta moved strictly inside: each P_k's eigenvalues raised to at least `fraction` times its
/// largest, the nonnegative scalars to `fraction` times the scale strictly_feasible uses.
Eigen::VectorXd pushed_inside(const ConeLayout& layout, const Eigen::VectorXd& theta, double fraction);

/// The smallest eigenvalue of any P_k and the smallest nonnegative scalar (+inf when the layout has
/// neither).
double primal_min(const ConeLayout& layout, const Eigen::VectorXd& theta);

/// min f over the cone, from the strictly feasible theta0: barrier stages mu_k decreasing
/// geometrically from 1e-2 f(theta0) / nu to 1e-14 / nu, each solved by Newton's method with a
/// backtracking line search that keeps theta inside; after each stage whose iterate points to a
/// face not tried yet, the face solve (solve_on_face), accepted when it reaches a KKT point (then
/// the path stops there). At most max_iterations Newton steps in all. Cost per step: one
/// evaluation of f with its Hessian, O(p^3) for the step and O(K) 4 x 4 eigensolvers per trial.
SolveResult solve_constrained(const Criterion& f, const ConeLayout& layout, const Eigen::VectorXd& theta0,
                              int max_iterations);

/// min f over the face of the cone that `guess` (any theta, inside the cone or not) points to: the
/// rank r_k of each P_k = the eigenvalues of P_k(guess) above 1e-3 of its largest, P_k = L_k L_k^T
/// with L_k 4 x r_k (so no constraint is left), the nonnegative scalars above the same fraction
/// free and the others fixed at 0, the free parameters free; Newton's method with a
/// Levenberg-Marquardt shift, at most max_steps steps. The result when it converges to a point that
/// satisfies the KKT conditions of the whole problem (dual_min_eig >= -kDualTolerance), else
/// nothing; *steps_taken counts the steps either way.
std::optional<SolveResult> solve_on_face(const Criterion& f, const ConeLayout& layout, const Eigen::VectorXd& guess,
                                         int max_steps, int* steps_taken = nullptr);

/// min f without constraints, from theta0: Newton's method with a Levenberg-Marquardt shift and a
/// backtracking line search. Fails (converged false) when the iterates grow beyond 1e8 times the
/// start's size (no minimum).
SolveResult solve_unconstrained(const Criterion& f, const Eigen::VectorXd& theta0, int max_iterations);

/// The KKT numbers of theta (ConeCertificate). NaN when f cannot be evaluated there.
ConeCertificate kkt_certificate(const Criterion& f, const ConeLayout& layout, const Eigen::VectorXd& theta);

}  // namespace spdfit::physical::detail
