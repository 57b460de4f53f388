// Internal: the checks and classification of a noise model's covariance matrices, shared by its
// factories.
#pragma once

#include <Eigen/Core>
#include <string>

namespace spdfit::detail {

/// What a symmetric covariance matrix is, to working precision.
struct CovarianceClass {
  bool zero = true;               ///< every entry exactly 0
  bool positive_definite = false;  ///< lambda_min > 64 n eps |lambda_max|
  bool semidefinite = true;        ///< lambda_min >= -64 n eps |lambda_max|
  double min_eigenvalue = 0.0, max_eigenvalue = 0.0;
};

/// The class of the symmetric S (an empty S is zero). Cost O(n^3).
CovarianceClass classify_covariance(const Eigen::MatrixXd& S);

/// S's symmetric part, after checking that S is a covariance matrix: non-empty, square, finite,
/// symmetric to 1e-10 of its largest entry, positive semidefinite to rounding. Throws
/// std::invalid_argument naming `option` (a library name in backticks) otherwise.
Eigen::MatrixXd checked_covariance(const Eigen::MatrixXd& S, const std::string& option);

/// "%.6g"-style text for the noise model's messages.
std::string number(double value);

/// An option's library name without the backticks messages put around it ("`rest_a`" -> "rest_a"):
/// the subject of an error about it.
inline std::string bare(const std::string& option) {
  std::string out;
  for (char c : option) {
    if (c != '`') out += c;
  }
  return out;
}

}  // namespace spdfit::detail
