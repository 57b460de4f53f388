// Internal: the optimizer of physical identification (hexapod/physical.hpp). The criterion and
// its exact derivatives in the parameters theta, minimized by the solver that every physically
// consistent fit shares (physical/cone_solver.hpp: the log-det barrier of the pseudo-inertia cone,
// Newton's method along a decreasing barrier weight, face solves, the KKT numbers of the result).
// Everything works in the triangular factor's scaled units (TriangularFactor).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hexapod/physical_model.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::hexapod::detail {

/// One fit's data in the factor's scaled units: A_s = A 2^-ea, B_s = B 2^-eb, so that
/// M_s = 2^(ea - eb) M and theta_s = 2^(ea - eb) theta (the cone is invariant under that scaling).
struct PhysicalData {
  PhysicalCriterion criterion = PhysicalCriterion::ErrorsInVariables;
  Matrix6d R11, R12, R22, E22;  ///< blocks of the factor; E22 = R22^T R22
  Matrix6d noise_a, noise_b;    ///< Sigma_A 2^-2ea, Sigma_B 2^-2eb
  Matrix6d M0;                  ///< the model's M0, scaled
  double theta_scale = 1.0;     ///< 2^(ea - eb)
  std::vector<Matrix6d> X;      ///< R11 D_a
  std::vector<Matrix6d> Q;      ///< R11^T R11 D_a
  std::vector<Matrix6d> SD;     ///< Sigma_A D_a (scaled)
  double f0 = 1.0;              ///< the normalization of the criterion (set_normalization)
};

/// The data of `factor` (n = d = 6) for the model; Sigma_A, Sigma_B in the data's units (empty:
/// identity). Cost O(p) 6 x 6 products.
PhysicalData physical_data(const TriangularFactor& factor, const PhysicalModel& model, PhysicalCriterion criterion,
                           const Eigen::MatrixXd& noise_a, const Eigen::MatrixXd& noise_b);

/// The criterion (unnormalized, scaled units) at M_s.
double raw_criterion(const PhysicalData& data, const Matrix6d& M_s);

/// f0: for least squares ||B_s||_F^2; for errors-in-variables sum_i b_i^T W^-1 b_i with the weight
/// W = M Sigma_A M + Sigma_B of the start M_s (the forces themselves as residuals: the data's own
/// scale, finite whenever the start's weight is positive definite). False when it is not.
bool set_normalization(PhysicalData& data, const PhysicalModel& model, const ParamVector& theta_start);

/// The criterion f / f0 at theta_s (scaled units) with its gradient (order >= 1) and Hessian
/// (order 2) in theta_s. False when the weight W is not positive definite.
struct Evaluation {
  double f = 0.0;
  ParamVector g;
  ParamMatrix H;
};
bool evaluate(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta, int order,
              Evaluation& out);

/// The unconstrained least-squares theta_s: min ||R11 M(theta) - R12||_F by a QR of the 36 x p
/// design [vec(R11 D_a)] (columns scaled). Also its rank under `cutoff` (relative).
ParamVector unconstrained_least_squares(const PhysicalData& data, const PhysicalModel& model, double cutoff,
                                        Eigen::Index* rank = nullptr, Eigen::MatrixXd* null_space = nullptr);

/// True when theta_s is strictly inside the cone: P > 0 (Cholesky) and every strut mass > 0.
bool strictly_feasible(const PhysicalModel& model, const ParamVector& theta);

/// theta moved strictly inside: P's eigenvalues and the strut masses raised to at least
/// `fraction` times the largest eigenvalue of P.
ParamVector pushed_inside(const PhysicalModel& model, const ParamVector& theta, double fraction);

/// How a minimization ended.
struct SolveResult {
  ParamVector theta;       ///< scaled units
  double f = 0.0;          ///< f / f0 at theta
  int iterations = 0;      ///< Newton steps
  bool converged = false;  ///< the last stage's stopping rule held
  std::string message;     ///< why not, when not converged
};

/// min f over the cone, from the strictly feasible theta0: barrier stages mu_k decreasing
/// geometrically to rounding level, each solved by Newton's method with a backtracking line search
/// that keeps P > 0; after each stage whose iterate points to a face not tried yet, the face solve
/// (solve_on_face), accepted when it reaches a KKT point (then the path stops there).
SolveResult solve_constrained(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta0,
                              int max_iterations);

/// min f over the face of the cone that `guess` (any theta_s, inside the cone or not) points to:
/// the rank r of P = the eigenvalues of P(guess) above 1e-3 of its largest, P = L L^T with L
/// 4 x r (Burer-Monteiro, so no constraint is left), the strut masses above the same fraction
/// free and the others fixed at 0; Newton's method with a Levenberg-Marquardt shift from the
/// factor of guess's clipped P, at most max_steps steps. The result when it converges to a point
/// that satisfies the KKT conditions of the whole problem (the multipliers of the active
/// constraints >= -1e-9), else nothing; *steps_taken counts the steps either way.
std::optional<SolveResult> solve_on_face(const PhysicalData& data, const PhysicalModel& model, const ParamVector& guess,
                                         int max_steps, int* steps_taken = nullptr);

/// min f without constraints, from theta0: Newton's method with a Levenberg-Marquardt shift and
/// a backtracking line search.
SolveResult solve_unconstrained(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta0,
                                int max_iterations);

/// The KKT numbers of theta_s (PhysicalCertificate's definitions; primal_min_eig back in kg).
PhysicalCertificate kkt_certificate(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta);

}  // namespace spdfit::hexapod::detail
