// Internal: total least squares with a noise model (tls, tls-sym and tls-psd with FitOptions::noise):
// generalized TLS by whitening, mixed with least squares for the directions of A without noise.
#pragma once

#include <Eigen/Core>

#include "estimators/noise_weights.hpp"

namespace spdfit::detail {

/// What generalized_tls returns, in the factor's scaled units.
struct GeneralizedTls {
  Eigen::MatrixXd X_s;         ///< n x d, when exists
  bool least_squares = false;  ///< Sigma_A = 0: X is least squares, A^+ B; the sigmas below are unset
  /// The directions of A without noise (eigenvalues of Sigma_A zero to rounding), fitted by least
  /// squares (mixed LS-TLS); n when least_squares.
  Eigen::Index exact_directions = 0;
  /// As TlsKernel's, for the whitened data (noise of unit variance in every remaining direction),
  /// so dimensionless: sigma_n and sigma_{n+1} of the TLS part, the correction norm (about
  /// sqrt(d (m - n)) when the noise model is right), V22's smallest singular value.
  double sigma_n = 0.0, sigma_n1 = 0.0, correction = 0.0, v22_min = 0.0;
  bool exists = false;
  bool unique = false;
};

/// Generalized TLS (Van Huffel & Vandewalle 1989): with Sigma_A = V diag(s) V^T, the exact
/// directions of A (s = 0) first and the others whitened, T_A = [V_0, V_1 diag(s_1)^-1/2], and
/// T_B = Sigma_B^-1/2, TLS fits [A T_A, B T_B] (noise of unit variance in every column) with the
/// first columns exact (mixed LS-TLS: TLS on the part of the factor orthogonal to them, then least
/// squares for the rest), and X = T_A X~ T_B^-1. Needs Sigma_B > 0 unless Sigma_A = 0, which is
/// least squares (noise_refusal checks). O((n + d)^3).
void generalized_tls(const DynamicReduction& data, const ScaledNoise& noise, GeneralizedTls& out);

}  // namespace spdfit::detail
