// Identifying a hexapod's M_p from logged accelerations and forces with every estimator, and
// what each estimate implies (eigenvalues, modes).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"

namespace spdfit::hexapod {

/// One estimator's estimate of M_p and what it implies.
struct MethodIdentification {
  FitResult result;                            ///< the estimate, diagnostics and warnings
  std::optional<Eigen::VectorXd> eigenvalues;  ///< of the estimate, ascending; when it is symmetric
  /// sqrt(eig(X^-1 K)) / (2 pi) in Hz, ascending; when the estimate is symmetric positive
  /// definite and a stiffness was given (an indefinite "mass matrix" has no modes).
  std::optional<Eigen::VectorXd> modes_hz;
  std::optional<double> error_vs_truth;  ///< ||X - truth||_F, when a truth was given
  /// With options.fit.bootstrap > 0: the bootstrap uncertainty of modes_hz (the eigenvalues' is
  /// result.bootstrap->eigenvalues), when modes_hz is present.
  std::optional<SpectrumUncertainty> modes_uncertainty;
};

/// Options of identify.
struct IdentifyOptions {
  std::optional<Eigen::MatrixXd> truth;      ///< the true M_p (n x n), to report errors
  std::optional<Eigen::MatrixXd> stiffness;  ///< K (n x n, symmetric), to report modes
  FitOptions fit;
};

/// Every estimator (kAllMethods, sharing one QR of [A B]) on accelerations A and forces B
/// (m x n each, one sample per row: B ~= A M_p, thesis eq. 3.1 in row form), with each
/// estimate's eigenvalues, the modes it implies with stiffness K (thesis section 2.2), and its
/// error against a known truth. Failed estimators are reported with their message.
///
/// With options.fit.bootstrap = N > 0, every estimator's result also carries its bootstrap
/// (FitResult::bootstrap: standard errors, intervals, bias, eigenvalue intervals) and, with a
/// stiffness, the modes' intervals: N multinomial resamples of the rows, each refitted by every
/// estimator (one shared factor per resample), on options.fit.threads threads. Cost N times the
/// estimators' O(m n^2 + n^3).
///
/// Preconditions: as fit_all; truth and stiffness n x n (else std::invalid_argument).
/// Cost: O(m n^2 + n^3).
std::vector<MethodIdentification> identify(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                           const IdentifyOptions& options = {});

}  // namespace spdfit::hexapod
